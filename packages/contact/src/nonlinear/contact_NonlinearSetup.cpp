#include "contact_NonlinearSetup.hpp"

#include <stdexcept>
#include <string>
#include <vector>

#include "contact_ContactParameters.hpp"
#include "contact_NonlinearModel.hpp"

namespace contact {

using Teuchos::ParameterList;

ElasticContactSpec nonlinearContactSpec(const ParameterList& params) {
  // The same bodies, loads and contact pair as elastic_contact, 2D or 3D as the mesh is.
  return elasticContactSpec(params);
}

NonlinearHistory readRestart(const std::string& restartDir, const ElasticContactProblem& problem,
                             std::vector<SubdomainRestart>& subdomains, FrictionHistory* friction) {
  NonlinearHistory history = readRestartState(restartDir);
  const std::string stepDir = restartStepDirectory(restartDir, history.step);
  if (friction) *friction = readFrictionRestart(stepDir);
  subdomains.clear();
  for (const auto& local : problem.local) {
    subdomains.push_back(readSubdomainRestart(stepDir, local.mesh.id));
    const SubdomainRestart& s = subdomains.back();
    if (s.displacement.size() != local.f.size())
      throw std::runtime_error(stepDir + ": subdomain " + std::to_string(s.id) + " has " +
                               std::to_string(s.displacement.size()) +
                               " displacement values, the mesh " + std::to_string(local.f.size()) +
                               " (restart with the same mesh and subdomains)");
  }
  return history;
}

double requireLoad(const tfeti::Comm& comm, const std::vector<tfeti::SubdomainData>& local) {
  Field f;
  for (const auto& s : local) f.push_back(s.f);
  const double norm = globalNorm(comm, f);
  if (!(norm > 0.0)) throw std::invalid_argument("Contact problem: no load is applied");
  return norm;
}

double requireLoadOrMotion(const tfeti::Comm& comm, const std::vector<tfeti::SubdomainData>& local,
                           const NonlinearOptions& options, bool prescribedMotion) {
  if (options.obstacleDisplacement.empty() && !prescribedMotion) return requireLoad(comm, local);
  Field f;
  for (const auto& s : local) f.push_back(s.f);
  return globalNorm(comm, f);
}

}  // namespace contact
