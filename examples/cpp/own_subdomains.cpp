// Guide program 1 (docs/cpp_guide.md): one's own subdomain matrices and one's own constraints.
//
// Laplace's equation on (0, 2) x (0, 1), torn into a strip of 4 subdomains along x, each
// assembled here (bilinear squares) into a Tpetra::CrsMatrix. The constraints are the caller's
// rows: u = 1 on the edge x = 0 (a non-zero Dirichlet value) and a multi-point constraint that
// makes the edge x = 2 one equipotential (u there equal to u at its bottom node). A flux Q leaves
// through one corner of that edge. The constraint spreads the flux over the edge, so the exact
// solution is u = 1 - Q x, which bilinear elements reproduce: the program checks the solution,
// gathered on a map of its own, against it and exits non-zero when it is wrong.
#include <Teuchos_DefaultSerialComm.hpp>
#include <Tpetra_Core.hpp>

#include <algorithm>
#include <cmath>
#include <iostream>

#include "tfeti_FetiSolver.hpp"

namespace {
constexpr int kSubdomains = 4;                    // strips along x
constexpr int kEx = 4, kEy = 8;                   // elements per subdomain
constexpr int kNodesX = kSubdomains * kEx + 1;    // untorn grid of nodes
constexpr double kH = 2.0 / (kSubdomains * kEx);  // square elements: 0.125
constexpr double kFlux = 0.25;                    // Q

// The untorn (global) id of grid node (i, j): the ids the gluing is built from.
tfeti::GO globalId(int i, int j) {
  return static_cast<tfeti::GO>(j) * kNodesX + i;
}
// The local number of node (a, j) of a subdomain: a = 0 .. kEx along x, j = 0 .. kEy.
int localId(int a, int j) {
  return j * (kEx + 1) + a;
}

// Subdomain s: its mesh (coordinates, elements, global ids) and K assembled into a CrsMatrix
// that lives on this rank alone (rows 0 .. n-1 = the local dofs).
tfeti::SubdomainData makeSubdomain(int s) {
  tfeti::SubdomainData d;
  d.mesh.id = s;
  d.mesh.dim = 2;
  for (int j = 0; j <= kEy; ++j)
    for (int a = 0; a <= kEx; ++a) {
      const int i = s * kEx + a;
      d.mesh.coords.push_back(i * kH);
      d.mesh.coords.push_back(j * kH);
      d.mesh.globalNode.push_back(globalId(i, j));
    }
  // Nothing in dirichletNodes: the subdomain floats, and u = 1 on x = 0 is a row of our own.
  const int n = d.mesh.numNodes();
  auto self = Teuchos::rcp(new Teuchos::SerialComm<int>());
  auto rows = Teuchos::rcp(new tfeti::Map(n, 0, self));
  auto K = Teuchos::rcp(new tfeti::CrsMatrix(rows, 9));
  // The Q1 stiffness of -Laplace on a square (independent of its size), counter-clockwise nodes.
  static const double ke[4][4] = {
      {4, -1, -2, -1}, {-1, 4, -1, -2}, {-2, -1, 4, -1}, {-1, -2, -1, 4}};
  for (int j = 0; j < kEy; ++j)
    for (int a = 0; a < kEx; ++a) {
      const int q[4] = {localId(a, j), localId(a + 1, j), localId(a + 1, j + 1), localId(a, j + 1)};
      d.mesh.elements.add({q[0], q[1], q[2], q[3]});
      for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c) {
          const tfeti::GO col = q[c];
          const double v = ke[r][c] / 6.0;
          K->insertGlobalValues(q[r], Teuchos::ArrayView<const tfeti::GO>(&col, 1),
                                Teuchos::ArrayView<const double>(&v, 1));
        }
    }
  K->fillComplete();
  d.tpetraK = K;
  // The load: the flux Q leaves through the top right corner (a node of the last subdomain).
  d.f.assign(n, 0.0);
  if (s == kSubdomains - 1) d.f[localId(kEx, kEy)] = -kFlux;
  return d;
}
}  // namespace

int main(int argc, char** argv) {
  Tpetra::ScopeGuard scope(&argc, &argv);
  auto comm = Tpetra::getDefaultComm();
  const int rank = comm->getRank();

  // Each rank passes the subdomains it holds: any split works, each id on exactly one rank.
  std::vector<tfeti::SubdomainData> local;
  for (int s : tfeti::subdomainsOfRank(rank, kSubdomains, comm->getSize()))
    local.push_back(makeSubdomain(s));

  // The caller's equality rows, sum coef * u = rhs over (subdomain, local dof). Each row is
  // passed once, by any one rank: here rank 0 passes them all.
  std::vector<tfeti::EqualityRow> rows;
  if (rank == 0) {
    for (int j = 0; j <= kEy; ++j)  // u = 1 on x = 0 (subdomain 0)
      rows.push_back({{{0, localId(0, j), 1.0}}, 1.0});
    const int last = kSubdomains - 1;  // u(2, y) - u(2, 0) = 0: the edge x = 2 is one value
    for (int j = 1; j <= kEy; ++j)
      rows.push_back({{{last, localId(kEx, j), 1.0}, {last, localId(kEx, 0), -1.0}}, 0.0});
  }

  Teuchos::ParameterList params;
  params.set("Formulation", "TFETI");
  params.set("Gluing", "nonredundant");  // "none": our rows would have to join the subdomains
  params.set("Preconditioner", "dirichlet");
  params.sublist("PCPG").set("Relative tolerance", 1e-10);
  tfeti::FetiSolver solver(comm, kSubdomains, std::move(local), params, {}, rows);
  const tfeti::DualResult result = solver.solve();

  // The solution on a map of our own: the untorn nodes, in contiguous blocks over the ranks.
  const tfeti::GO numNodes = static_cast<tfeti::GO>(kNodesX) * (kEy + 1);
  auto untorn = Teuchos::rcp(new tfeti::Map(numNodes, 0, comm));
  auto u = solver.solution(untorn);
  auto values = u->getData(0);
  double error = 0.0;
  for (std::size_t k = 0; k < values.size(); ++k) {
    const tfeti::GO g = untorn->getGlobalElement(static_cast<int>(k));
    const double x = static_cast<double>(g % kNodesX) * kH;
    error = std::max(error, std::abs(values[k] - (1.0 - kFlux * x)));
  }
  double maxError = 0.0;
  Teuchos::reduceAll(*comm, Teuchos::REDUCE_MAX, 1, &error, &maxError);
  const double rowResidual = solver.constraintReport().equalityResidual;

  if (rank == 0)
    std::cout << "own_subdomains: " << result.iterations << " PCPG iterations, "
              << solver.userEqualityRows() << " rows of ours, " << solver.gluingRows()
              << " gluing rows, max |u - (1 - Q x)| = " << maxError
              << ", max |B_E u - c_E| = " << rowResidual << "\n";
  // The closed form is in the finite-element space: only the solver's tolerance remains.
  const bool ok = result.converged && maxError < 1e-8 && rowResidual < 1e-8;
  if (!ok && rank == 0) std::cerr << "own_subdomains: WRONG ANSWER\n";
  return ok ? 0 : 1;
}
