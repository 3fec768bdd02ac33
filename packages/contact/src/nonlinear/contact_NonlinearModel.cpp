#include "contact_NonlinearModel.hpp"

#include <Teuchos_CommHelpers.hpp>

#include <algorithm>
#include <cmath>

#include "tfeti_Gather.hpp"

namespace contact {

double globalNorm(const tfeti::Comm& comm, const Field& v) {
  double local = 0.0, global = 0.0;
  for (const auto& x : v)
    for (double y : x) local += y * y;
  Teuchos::reduceAll(comm, Teuchos::REDUCE_SUM, 1, &local, &global);
  return std::sqrt(global);
}

double globalMax(const tfeti::Comm& comm, double local) {
  double global = 0.0;
  Teuchos::reduceAll(comm, Teuchos::REDUCE_MAX, 1, &local, &global);
  return global;
}

std::vector<double> NonlinearModel::surfaceDisplacement(const tfeti::Comm& comm,
                                                        const Field& disp) const {
  const int d = dim();
  std::vector<char> onSurface(problem.mesh.numNodes(), 0);
  for (int n : problem.surfaceNodes) onSurface[n] = 1;
  // (global node, d components) per surface node whose first copy is here.
  std::vector<double> mine;
  for (std::size_t i = 0; i < problem.local.size(); ++i) {
    const auto& mesh = problem.local[i].mesh;
    for (int n = 0; n < mesh.numNodes(); ++n) {
      const int g = static_cast<int>(mesh.globalNode[n]);
      if (!onSurface[g] || problem.copyOf[g].first != mesh.id) continue;
      mine.push_back(static_cast<double>(g));
      for (int c = 0; c < d; ++c) mine.push_back(disp[i][d * n + c]);
    }
  }
  const std::vector<double> all = tfeti::allGather(comm, mine);
  std::vector<double> out(static_cast<std::size_t>(d) * problem.mesh.numNodes(), 0.0);
  for (std::size_t k = 0; k + d < all.size(); k += d + 1) {
    const auto g = static_cast<std::size_t>(all[k]);
    for (int c = 0; c < d; ++c) out[d * g + c] = all[k + 1 + c];
  }
  return out;
}

Field NonlinearModel::currentCoordinates(const Field& disp) const {
  Field x;
  for (std::size_t i = 0; i < disp.size(); ++i) {
    x.push_back(problem.localElements[i].coords);
    for (std::size_t k = 0; k < x[i].size(); ++k) x[i][k] += disp[i][k];
  }
  return x;
}

Field NonlinearModel::kernelCoordinates(const Field& disp, plasticity::Kinematics kin) const {
  if (kin == plasticity::Kinematics::TotalLagrangian) return currentCoordinates(disp);
  Field x;
  for (std::size_t i = 0; i < disp.size(); ++i) x.push_back(problem.localElements[i].coords);
  return x;
}

Field NonlinearModel::internalForce(const Field& disp, plasticity::Kinematics kin) const {
  Field f;
  for (std::size_t i = 0; i < laws.size(); ++i)
    f.push_back(plasticity::internalForce(problem.localElements[i], *laws[i], disp[i], kin));
  return f;
}

std::vector<tfeti::CsrMatrix> NonlinearModel::tangent(const Field& disp, plasticity::Kinematics kin,
                                                      const std::vector<char>& keep) const {
  std::vector<tfeti::CsrMatrix> K(disp.size());
  for (std::size_t i = 0; i < disp.size(); ++i)
    if (keep.empty() || !keep.at(i))
      K[i] = plasticity::tangentStiffness(problem.localElements[i], *laws[i], disp[i], kin, false);
  return K;
}

std::vector<char> NonlinearModel::plasticLoadingPerSubdomain() const {
  std::vector<char> loading(plastic.size(), 0);
  for (std::size_t i = 0; i < plastic.size(); ++i) {
    const auto* p = plastic[i];
    if (p == nullptr) continue;
    for (int e = 0; e < p->numElements() && !loading[i]; ++e)
      for (int g = 0; g < p->gaussPointsPerElement(); ++g)
        if (p->trialEquivalentPlasticStrain({e, g}) > p->equivalentPlasticStrain({e, g})) {
          loading[i] = 1;
          break;
        }
  }
  return loading;
}

bool NonlinearModel::plasticLoading(const tfeti::Comm& comm) const {
  int local = 0;
  for (char l : plasticLoadingPerSubdomain()) local = l ? 1 : local;
  int any = 0;
  Teuchos::reduceAll(comm, Teuchos::REDUCE_MAX, 1, &local, &any);
  return any == 1;
}

void NonlinearModel::commit() {
  for (auto* p : plastic)
    if (p) p->commit();
}

void NonlinearModel::revert() {
  for (auto* p : plastic)
    if (p) p->revert();
}

NonlinearModel makeNonlinearModel(ElasticContactProblem problem,
                                  const std::vector<ElasticContactSpec::Body>& bodies) {
  NonlinearModel model;
  model.problem = std::move(problem);
  const ElasticContactProblem& p = model.problem;
  // A subdomain is part of one body (each body is partitioned on its own), so one law object
  // per subdomain carries that body's material.
  for (std::size_t i = 0; i < p.local.size(); ++i) {
    const ElasticContactSpec::Body& body = bodies.at(p.localBody[i]);
    const auto& em = p.localElements[i];
    if (body.yieldStress > 0.0) {
      auto j2 = std::make_unique<plasticity::J2PlasticMaterial>(
          body.law.E, body.law.nu, body.yieldStress, body.hardening, em.numElements(),
          plasticity::numGaussPoints(em.type));
      model.plastic.push_back(j2.get());
      model.laws.push_back(std::move(j2));
    } else {
      model.plastic.push_back(nullptr);
      model.laws.push_back(std::make_unique<plasticity::LinearElasticMaterial>(body.law));
    }
    model.externalLoad.push_back(p.local[i].f);
    model.u.emplace_back(p.local[i].f.size(), 0.0);
  }
  return model;
}

double plasticStrain(const plasticity::J2PlasticMaterial* law, const plasticity::ElementMesh& em,
                     std::vector<double>& nodal) {
  nodal.assign(em.numNodes(), 0.0);
  if (!law) return 0.0;
  std::vector<int> count(em.numNodes(), 0);
  const int npe = plasticity::nodesPerElement(em.type), ngp = law->gaussPointsPerElement();
  double mx = 0.0;
  for (int e = 0; e < em.numElements(); ++e) {
    double mean = 0.0;
    for (int q = 0; q < ngp; ++q) {
      const double a = law->trialEquivalentPlasticStrain({e, q});
      mx = std::max(mx, a);
      mean += a / ngp;
    }
    for (int k = 0; k < npe; ++k) {
      const int n = em.connectivity[static_cast<std::size_t>(e) * npe + k];
      nodal[n] += mean;
      ++count[n];
    }
  }
  for (int n = 0; n < em.numNodes(); ++n)
    if (count[n] > 0) nodal[n] /= count[n];
  return mx;
}

}  // namespace contact
