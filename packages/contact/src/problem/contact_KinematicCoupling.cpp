#include "contact_KinematicCoupling.hpp"

#include <Teuchos_CommHelpers.hpp>

#include <algorithm>
#include <limits>
#include <map>
#include <set>
#include <stdexcept>

#include "contact_PrescribedDisplacement.hpp"

namespace contact {

using Teuchos::Array;

namespace {

std::string componentName(int c) {
  return std::string("u_") + "xyz"[c % 3];
}

}  // namespace

void addKinematicCouplingParameters(Teuchos::ParameterList& list) {
  list.set("Coupled boundaries", Array<std::string>(),
           "boundaries whose nodes share one common, unknown value of a component (a kinematic "
           "coupling: a rigid loading plate that does not rotate); one entry per coupled "
           "component, a name may repeat");
  list.set("Coupled components", Array<int>(),
           "the coupled component (0: x, 1: y, 2: z) of each Coupled boundaries entry",
           componentsValidator());
}

std::vector<KinematicCoupling> kinematicCouplings(const Teuchos::ParameterList& list,
                                                  const std::string& where) {
  const auto names = list.get<Array<std::string>>("Coupled boundaries");
  const auto components = list.get<Array<int>>("Coupled components");
  if (components.size() != names.size())
    throw std::invalid_argument(where +
                                ": \"Coupled boundaries\" and \"Coupled components\" need one "
                                "entry per coupled component (got " +
                                std::to_string(names.size()) + " and " +
                                std::to_string(components.size()) + ")");
  std::vector<KinematicCoupling> out;
  std::set<std::pair<std::string, int>> seen;
  for (int k = 0; k < static_cast<int>(names.size()); ++k) {
    if (!seen.insert({names[k], components[k]}).second)
      throw std::invalid_argument(where + "/Coupled boundaries: \"" + names[k] + "\" couples " +
                                  componentName(components[k]) + " twice");
    out.push_back({names[k], components[k]});
  }
  return out;
}

std::vector<tfeti::EqualityRow> kinematicCouplingRows(
    const std::vector<KinematicCoupling>& couplings, const CouplingContext& context) {
  const int dim = context.dim;
  std::vector<tfeti::EqualityRow> rows;
  std::map<std::pair<long long, int>, std::string> coupledBy;
  for (const KinematicCoupling& k : couplings) {
    if (k.component < 0 || k.component >= dim)
      throw std::invalid_argument("Coupled components: " + std::to_string(k.component) +
                                  " for boundary \"" + k.boundary + "\" is not " +
                                  (dim == 3 ? "0 (x), 1 (y) or 2 (z)" : "0 (x) or 1 (y)") + " (a " +
                                  std::to_string(dim) + "D problem)");
    std::vector<long long> nodes = context.nodesOf(k.boundary);
    std::sort(nodes.begin(), nodes.end());
    nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
    if (nodes.size() < 2)
      throw std::invalid_argument("Coupled boundaries: \"" + k.boundary + "\" has " +
                                  std::to_string(nodes.size()) +
                                  " node(s); a coupling ties two or more");
    const std::string what = componentName(k.component) + " of \"" + k.boundary + "\"";
    for (long long n : nodes) {
      const std::string held = context.heldBy(n, k.component);
      if (!held.empty())
        throw std::invalid_argument("Coupled boundaries: the coupling of " + what + " meets the " +
                                    held +
                                    " at a node; a coupled component must be free (prescribe it "
                                    "on the boundary instead of coupling it)");
      const auto [it, added] = coupledBy.insert({{n, k.component}, k.boundary});
      if (!added)
        throw std::invalid_argument("Coupled boundaries: \"" + k.boundary + "\" and \"" +
                                    it->second + "\" couple " + componentName(k.component) +
                                    " at a common node; join them into one boundary");
    }
    const auto [s0, l0] = context.firstCopy(nodes.front());
    for (std::size_t j = 1; j < nodes.size(); ++j) {
      const auto [s, l] = context.firstCopy(nodes[j]);
      rows.push_back({{{s, dim * l + k.component, 1.0}, {s0, dim * l0 + k.component, -1.0}}, 0.0});
    }
  }
  return rows;
}

Json couplingSummary(const tfeti::Comm& comm, const std::vector<KinematicCoupling>& couplings,
                     const std::vector<tfeti::SubdomainData>& local,
                     const std::vector<std::vector<double>>& u,
                     const std::function<std::vector<long long>(const std::string&)>& nodesOf) {
  Json list = Json::array();
  for (const KinematicCoupling& k : couplings) {
    const std::vector<long long> ids = nodesOf(k.boundary);
    const std::set<long long> nodes(ids.begin(), ids.end());
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (std::size_t i = 0; i < local.size(); ++i) {
      const auto& sd = local[i];
      for (int n = 0; n < sd.mesh.numNodes(); ++n)
        if (nodes.count(sd.mesh.globalNode[n])) {
          const double v = u[i].at(sd.dofsPerNode * n + k.component);
          lo = std::min(lo, v);
          hi = std::max(hi, v);
        }
    }
    double globalLo = lo, globalHi = hi;
    Teuchos::reduceAll(comm, Teuchos::REDUCE_MIN, 1, &lo, &globalLo);
    Teuchos::reduceAll(comm, Teuchos::REDUCE_MAX, 1, &hi, &globalHi);
    Json r = Json::object();
    r["boundary"] = k.boundary;
    r["component"] = k.component;
    r["nodes"] = static_cast<long long>(nodes.size());
    r["displacement"] = 0.5 * (globalLo + globalHi);
    r["spread"] = globalHi - globalLo;
    list.push(std::move(r));
  }
  return list;
}

}  // namespace contact
