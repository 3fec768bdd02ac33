// The two ways to columns of K+ on a subdomain's interface dofs, as the explicit dual operator
// assembles F_s = B_s K+ B_s^T (tfeti_ExplicitDualOperator.cpp): solves with 128 unit columns at
// a time, or the whole block at once from the Schur complement (LocalSolver::inverseBlock). A
// block assembled anew needs every column; a block whose contact rows moved needs only the
// changed ones. The crossover (how many columns cost what the whole block from the Schur
// complement costs) says which way such a partial reassembly should go.
//
//   build/bin/inverse_block_bench
//
// The matrices are elasticity subdomains of cells^dim Quad4 / Hex8 cells (E = 1, nu = 0.3) with
// the nodes of one face removed so that they are definite, factorized by the project's CHOLMOD
// solver; the dofs are those of the other boundary nodes, what a subdomain's gluing rows touch.
// Each time is the best of several repetitions.
#include <Kokkos_Core.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <vector>

#include "plasticity_ElasticLaw.hpp"
#include "plasticity_Q1Assembly.hpp"
#include "tfeti_LocalSolver.hpp"
#include "tfeti_StructuredMesh.hpp"

namespace {

double now() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

// Best time of pass() over repetitions taking at least 0.3 s in all (at least 3).
template <class Pass>
double best(Pass&& pass) {
  double t = 1e300, spent = 0.0;
  for (int r = 0; r < 3 || spent < 0.3; ++r) {
    const double s = now();
    pass();
    const double d = now() - s;
    t = std::min(t, d);
    spent += d;
  }
  return t;
}

struct Subdomain {
  tfeti::CsrMatrix K;     // without the dofs of the nodes on the face x_last = 0
  std::vector<int> dofs;  // the other boundary nodes' dofs, numbered in K
};

Subdomain subdomain(int dim, int cells) {
  plasticity::Q1Mesh mesh;
  mesh.dim = dim;
  const int m = cells + 1, nodes = dim == 2 ? m * m : m * m * m;
  for (int i = 0; i < nodes; ++i) {
    mesh.coords.push_back(i % m);
    mesh.coords.push_back((i / m) % m);
    if (dim == 3) mesh.coords.push_back(i / (m * m));
  }
  mesh.cells = tfeti::StructuredMesh::cells(std::vector<int>(dim, cells));
  const tfeti::CsrMatrix K = plasticity::assembleStiffness(mesh, plasticity::Field::Elasticity,
                                                           plasticity::ElasticLaw(1.0, 0.3));
  Subdomain s;
  std::vector<int> kept;
  for (int i = 0; i < nodes; ++i) {
    const int c[3] = {i % m, (i / m) % m, i / (m * m)};
    if (c[dim - 1] == 0) continue;  // the removed face: the matrix is definite without it
    bool boundary = false;
    for (int a = 0; a < dim; ++a) boundary = boundary || c[a] == 0 || c[a] == cells;
    for (int a = 0; a < dim; ++a) {
      if (boundary) s.dofs.push_back(static_cast<int>(kept.size()));
      kept.push_back(i * dim + a);
    }
  }
  s.K = K.submatrix(kept, kept);
  return s;
}

}  // namespace

int main(int argc, char** argv) {
  Kokkos::ScopeGuard kokkos(argc, argv);  // the element kernels of the assembly
  std::printf("%-4s %5s %6s %5s %12s %12s %12s %10s %8s\n", "dim", "cells", "n", "k", "schur s",
              "solve/col s", "all cols s", "crossover", "/ k");
  const int cases[][2] = {{2, 8}, {2, 16}, {2, 32}, {2, 64}, {3, 4}, {3, 6}, {3, 8}, {3, 10}};
  for (const auto& c : cases) {
    const Subdomain s = subdomain(c[0], c[1]);
    const int n = s.K.rows, k = static_cast<int>(s.dofs.size());
    auto solver = tfeti::createLocalSolver("cholmod");
    solver->factorize(s.K);
    std::vector<double> inv;
    const double tSchur = best([&] {
      if (!solver->inverseBlock(s.K, s.dofs, inv)) std::printf("no inverse block\n");
    });
    // The unit columns of the dofs, 128 per solve as the assembly takes them.
    std::vector<double> rhs(static_cast<std::size_t>(n) * k, 0.0), x(rhs.size());
    for (int j = 0; j < k; ++j) rhs[static_cast<std::size_t>(j) * n + s.dofs[j]] = 1.0;
    const double tAll = best([&] {
      for (int j = 0; j < k; j += 128)
        solver->solve(rhs.data() + static_cast<std::size_t>(j) * n,
                      x.data() + static_cast<std::size_t>(j) * n, std::min(128, k - j));
    });
    const double tCol = tAll / k;
    std::printf("%-4d %5d %6d %5d %12.3e %12.3e %12.3e %10.0f %8.2f\n", c[0], c[1], n, k, tSchur,
                tCol, tAll, tSchur / tCol, tSchur / tCol / k);
  }
}
