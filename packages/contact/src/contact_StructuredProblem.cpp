#include "contact_StructuredProblem.hpp"

#include <Teuchos_CommHelpers.hpp>

#include <algorithm>
#include <cmath>
#include <utility>

#include "plasticity_Q1Assembly.hpp"
#include "tfeti_LocalSolver.hpp"

namespace contact {

namespace {
tfeti::SubdomainData assemble(const StructuredProblem& p, tfeti::SubdomainMesh mesh,
                              std::vector<int> cells) {
  tfeti::SubdomainData sd;
  const plasticity::Q1Mesh q{mesh.coords, std::move(cells), p.dim()};
  const double* src = p.field == "poisson" ? &p.source : p.bodyForce.data();
  sd.K = plasticity::assembleStiffness(q, p.q1Field(), p.law);
  sd.f = plasticity::assembleBodyLoad(q, p.q1Field(), src);
  sd.dofsPerNode = p.dofsPerNode();
  sd.mesh = std::move(mesh);
  return sd;
}
}  // namespace

std::vector<tfeti::SubdomainData> buildLocalSubdomains(const StructuredProblem& problem,
                                                       const tfeti::Comm& comm) {
  const auto mesh = problem.mesh();
  std::vector<tfeti::SubdomainData> local;
  const std::vector<int> cells = mesh.subdomainCells();
  for (int s : tfeti::subdomainsOfRank(comm.getRank(), mesh.numSubdomains(), comm.getSize()))
    local.push_back(assemble(problem, mesh.subdomain(s), cells));
  return local;
}

double relativeErrorAgainstDirectSolve(const StructuredProblem& problem,
                                       const tfeti::FetiSolver& solver) {
  const tfeti::StructuredMesh mesh = problem.mesh();
  tfeti::SubdomainData whole = assemble(problem, mesh.wholeMesh(), mesh.wholeCells());
  const int dpn = whole.dofsPerNode;
  // Dirichlet dofs eliminated: rows and columns become the identity, zero load.
  std::vector<char> fixed(whole.K.rows, 0);
  for (int n : whole.mesh.dirichletNodes)
    for (int c = 0; c < dpn; ++c) fixed[n * dpn + c] = 1;
  auto& K = whole.K;
  for (int i = 0; i < K.rows; ++i)
    for (int k = K.rowPtr[i]; k < K.rowPtr[i + 1]; ++k)
      if (fixed[i] || fixed[K.colInd[k]]) K.values[k] = (i == K.colInd[k]) ? 1.0 : 0.0;
  for (int i = 0; i < K.rows; ++i)
    if (fixed[i]) whole.f[i] = 0.0;
  auto direct = tfeti::createLocalSolver("cholmod");
  direct->factorize(K);
  std::vector<double> u(K.rows);
  direct->solve(whole.f.data(), u.data());

  double maxErr = 0.0, maxRef = 0.0;
  for (double v : u) maxRef = std::max(maxRef, std::abs(v));
  for (std::size_t i = 0; i < solver.data().size(); ++i) {
    const auto& mesh = solver.data()[i].mesh;
    const auto& us = solver.solution(i);
    for (int n = 0; n < mesh.numNodes(); ++n)
      for (int c = 0; c < dpn; ++c)
        maxErr = std::max(maxErr, std::abs(us[n * dpn + c] - u[mesh.globalNode[n] * dpn + c]));
  }
  double globalErr = 0.0;
  Teuchos::reduceAll(*solver.comm(), Teuchos::REDUCE_MAX, 1, &maxErr, &globalErr);
  return maxRef > 0.0 ? globalErr / maxRef : globalErr;
}

}  // namespace contact
