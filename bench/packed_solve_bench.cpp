// One right-hand side through many subdomain factors, as a FETI Hessian multiplication does it:
// CHOLMOD's own supernodal solve against the packed solves of tfeti_PackedSupernodal.hpp, on the
// same factors, with the bytes each pass reads and the rate it reaches.
//
//   build/bin/packed_solve_bench [factors = 256] [cells per side = 8]
//
// The matrix is a trilinear-hexahedron elasticity subdomain (cells^3 Hex8, E = 1, nu = 0.3,
// the bottom face's nodes removed so that it is definite), ordered and factorized as the project's
// local solver does (the smaller of AMD's and METIS's factors, supernodal L L^T). `factors` copies
// of it are factorized so that they do not fit in any cache (256 of 8^3 cells: about 1 GB, what
// one rank holds at step-42's 64^3 on 2 ranks). Each pass solves one vector with every factor in
// turn; the best of five passes is reported.
#include <cholmod.h>
#include <Kokkos_Core.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "plasticity_ElasticLaw.hpp"
#include "plasticity_Q1Assembly.hpp"
#include "tfeti_PackedSupernodal.hpp"
#include "tfeti_StructuredMesh.hpp"

namespace {

double now() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

// The upper triangle of K without the dofs of the nodes at z = 0, as a CHOLMOD matrix.
cholmod_sparse* subdomainMatrix(int cells, cholmod_common* c) {
  plasticity::Q1Mesh mesh;
  mesh.dim = 3;
  const int m = cells + 1;
  for (int k = 0; k < m; ++k)
    for (int j = 0; j < m; ++j)
      for (int i = 0; i < m; ++i)
        mesh.coords.insert(mesh.coords.end(), {1.0 * i, 1.0 * j, 1.0 * k});
  mesh.cells = tfeti::StructuredMesh::cells({cells, cells, cells});  // x fastest, as coords
  const tfeti::CsrMatrix K = plasticity::assembleStiffness(mesh, plasticity::Field::Elasticity,
                                                           plasticity::ElasticLaw(1.0, 0.3));
  const int fixed = 3 * m * m, n = K.rows - fixed;  // the z = 0 nodes come first
  std::size_t nnz = 0;
  for (int r = fixed; r < K.rows; ++r)
    for (int p = K.rowPtr[r]; p < K.rowPtr[r + 1]; ++p) nnz += K.colInd[p] >= r;
  // CSR of the upper triangle of a symmetric matrix is CSC of its lower one: stored as stype -1.
  cholmod_sparse* A = cholmod_allocate_sparse(n, n, nnz, 1, 1, -1, CHOLMOD_REAL, c);
  int* Ap = static_cast<int*>(A->p);
  int* Ai = static_cast<int*>(A->i);
  double* Ax = static_cast<double*>(A->x);
  std::size_t z = 0;
  for (int r = fixed; r < K.rows; ++r) {
    Ap[r - fixed] = static_cast<int>(z);
    for (int p = K.rowPtr[r]; p < K.rowPtr[r + 1]; ++p)
      if (K.colInd[p] >= r) Ai[z] = K.colInd[p] - fixed, Ax[z++] = K.values[p];
  }
  Ap[n] = static_cast<int>(z);
  return A;
}

}  // namespace

int main(int argc, char** argv) {
  Kokkos::ScopeGuard kokkos(argc, argv);  // the element kernels of the assembly
  const int count = argc > 1 ? std::atoi(argv[1]) : 256;
  const int cells = argc > 2 ? std::atoi(argv[2]) : 8;
  cholmod_common c;
  cholmod_start(&c);
  c.final_ll = 1;
  c.supernodal = CHOLMOD_SUPERNODAL;
  c.nmethods = 2;
  c.method[0].ordering = CHOLMOD_AMD;
  c.method[1].ordering = CHOLMOD_METIS;
  cholmod_sparse* A = subdomainMatrix(cells, &c);
  const int n = static_cast<int>(A->nrow);
  cholmod_factor* symbolic = cholmod_analyze(A, &c);
  std::vector<cholmod_factor*> L(count);
  for (auto& f : L) {
    f = cholmod_copy_factor(symbolic, &c);
    if (!cholmod_factorize(A, f, &c) || c.status != CHOLMOD_OK) {
      std::fprintf(stderr, "factorization failed\n");
      return 1;
    }
  }
  const tfeti::PackedLayout layout = tfeti::packedLayout(*L[0]);
  const double padded = 8.0 * L[0]->xsize, packed = 8.0 * layout.offsets.back();
  std::printf(
      "%d factors of %d^3 Hex8 cells: n = %d, %zu supernodes, values %.2f MB (CHOLMOD) / "
      "%.2f MB (packed), all factors %.0f MB\n",
      count, cells, n, L[0]->nsuper, padded * 1e-6, packed * 1e-6, count * padded * 1e-6);

  cholmod_dense* b = cholmod_ones(n, 1, CHOLMOD_REAL, &c);
  for (int i = 0; i < n; ++i) static_cast<double*>(b->x)[i] = 1.0 + 1e-3 * i;
  cholmod_dense *X = nullptr, *Y = nullptr, *E = nullptr;
  auto best = [](auto&& pass) {
    double t = 1e300;
    for (int r = 0; r < 5; ++r) {
      const double s = now();
      pass();
      t = std::min(t, now() - s);
    }
    return t;
  };
  const double tL = best([&] {
    for (auto f : L) cholmod_solve2(CHOLMOD_L, f, b, nullptr, &X, nullptr, &Y, &E, &c);
  });
  const double tLt = best([&] {
    for (auto f : L) cholmod_solve2(CHOLMOD_Lt, f, b, nullptr, &X, nullptr, &Y, &E, &c);
  });
  const double tA = best([&] {
    for (auto f : L) cholmod_solve2(CHOLMOD_A, f, b, nullptr, &X, nullptr, &Y, &E, &c);
  });
  std::vector<double> reference(static_cast<double*>(X->x), static_cast<double*>(X->x) + n);

  std::vector<double> scratch, y(n), w(layout.maxRows), x(n);
  for (auto f : L) tfeti::packSupernodal(*f, layout, scratch);
  const double tPack = best([&] {
                         for (auto f : L)
                           tfeti::unpackSupernodal(*f, layout, scratch),
                               tfeti::packSupernodal(*f, layout, scratch);
                       }) /
                       2;
  const int* perm = static_cast<const int*>(L[0]->Perm);
  const double* bx = static_cast<const double*>(b->x);
  const double tF = best([&] {
    for (auto f : L) {
      for (int i = 0; i < n; ++i) y[i] = bx[perm[i]];
      tfeti::packedForwardSolve(*f, layout, y.data(), w.data());
    }
  });
  const double tB = best([&] {
    for (auto f : L) tfeti::packedBackwardSolve(*f, layout, y.data(), w.data());
  });
  const double tFB = best([&] {
    for (auto f : L) {
      for (int i = 0; i < n; ++i) y[i] = bx[perm[i]];
      tfeti::packedForwardSolve(*f, layout, y.data(), w.data());
      tfeti::packedBackwardSolve(*f, layout, y.data(), w.data());
      for (int i = 0; i < n; ++i) x[perm[i]] = y[i];
    }
  });
  // The packed solution's residual, with A's symmetric product.
  cholmod_dense* xd = cholmod_zeros(n, 1, CHOLMOD_REAL, &c);
  cholmod_dense* r = cholmod_copy_dense(b, &c);
  std::copy(x.begin(), x.end(), static_cast<double*>(xd->x));
  double minusOne[2] = {-1, 0}, one[2] = {1, 0};
  cholmod_sdmult(A, 0, minusOne, one, xd, r, &c);
  double rr = 0, bb = 0;
  for (int i = 0; i < n; ++i) {
    rr += std::pow(static_cast<const double*>(r->x)[i], 2);
    bb += std::pow(static_cast<const double*>(b->x)[i], 2);
  }
  const double residual = std::sqrt(rr / bb);
  cholmod_free_dense(&xd, &c), cholmod_free_dense(&r, &c);
  double diff = 0, size = 0;
  for (int i = 0; i < n; ++i) {
    const double d = std::abs(x[i] - reference[i]);
    diff = d <= diff ? diff : d;  // a NaN sticks
    size = std::max(size, std::abs(reference[i]));
  }

  const double gb = 1e-9 * count;
  std::printf("| pass | CHOLMOD ms | GB/s | packed ms | GB/s |\n|---|---|---|---|---|\n");
  std::printf("| forward (L) | %.1f | %.1f | %.1f | %.1f |\n", 1e3 * tL, gb * padded / tL, 1e3 * tF,
              gb * packed / tF);
  std::printf("| backward (L^T) | %.1f | %.1f | %.1f | %.1f |\n", 1e3 * tLt, gb * padded / tLt,
              1e3 * tB, gb * packed / tB);
  std::printf("| both, one factor after the other | %.1f | | %.1f | |\n", 1e3 * tA, 1e3 * tFB);
  std::printf(
      "packing one factor (either way): %.3f ms; packed against CHOLMOD: max difference %.2e "
      "of %.2e; residual ||b - A x|| / ||b|| %.1e\n",
      1e3 * tPack / count, diff, size, residual);
  for (auto& f : L) cholmod_free_factor(&f, &c);
  cholmod_free_factor(&symbolic, &c);
  cholmod_free_dense(&X, &c), cholmod_free_dense(&Y, &c), cholmod_free_dense(&E, &c);
  cholmod_free_dense(&b, &c);
  cholmod_free_sparse(&A, &c);
  cholmod_finish(&c);
  return diff <= 1e-12 * size && residual < 1e-10 ? 0 : 1;
}
