#include "plasticity_Q1Assembly.hpp"

#include <Kokkos_Core.hpp>

#include <algorithm>
#include <stdexcept>
#include <string>

namespace plasticity {
namespace {

using ExecSpace = Kokkos::DefaultHostExecutionSpace;
constexpr double kGauss = 0.57735026918962576451;  // 1/sqrt(3)

// Shape function derivatives at (xi, eta) mapped to x, y; returns the Jacobian determinant.
KOKKOS_INLINE_FUNCTION double q1Gradients(const double xe[8], double xi, double eta,
                                          double dN[4][2], double N[4]) {
  const double sx[4] = {-1, 1, 1, -1}, sy[4] = {-1, -1, 1, 1};
  double dXi[4][2];
  for (int a = 0; a < 4; ++a) {
    N[a] = 0.25 * (1 + sx[a] * xi) * (1 + sy[a] * eta);
    dXi[a][0] = 0.25 * sx[a] * (1 + sy[a] * eta);
    dXi[a][1] = 0.25 * sy[a] * (1 + sx[a] * xi);
  }
  double J[2][2] = {{0, 0}, {0, 0}};
  for (int a = 0; a < 4; ++a)
    for (int i = 0; i < 2; ++i)
      for (int j = 0; j < 2; ++j) J[i][j] += xe[2 * a + i] * dXi[a][j];
  const double det = J[0][0] * J[1][1] - J[0][1] * J[1][0];
  const double inv[2][2] = {{J[1][1] / det, -J[0][1] / det}, {-J[1][0] / det, J[0][0] / det}};
  for (int a = 0; a < 4; ++a)
    for (int j = 0; j < 2; ++j) dN[a][j] = dXi[a][0] * inv[0][j] + dXi[a][1] * inv[1][j];
  return det;
}

// Element coordinates gathered into a View so that the kernels see plain arrays.
Kokkos::View<double* [8], Kokkos::HostSpace> elementCoords(const QuadMesh& mesh) {
  const int ne = mesh.numElements();
  Kokkos::View<double* [8], Kokkos::HostSpace> xe("xe", ne);
  for (int e = 0; e < ne; ++e)
    for (int a = 0; a < 4; ++a) {
      const int n = mesh.quads[4 * e + a];
      xe(e, 2 * a) = mesh.coords[2 * n];
      xe(e, 2 * a + 1) = mesh.coords[2 * n + 1];
    }
  return xe;
}

void checkJacobians(const Kokkos::View<double*, Kokkos::HostSpace>& minDet) {
  for (std::size_t e = 0; e < minDet.extent(0); ++e)
    if (!(minDet(e) > 0.0))
      throw std::runtime_error("element " + std::to_string(e) +
                               " is degenerate or inverted (Jacobian determinant " +
                               std::to_string(minDet(e)) + ")");
}

}  // namespace

tfeti::CsrMatrix assembleStiffness(const QuadMesh& mesh, Field field, const ElasticLaw& law) {
  const int ne = mesh.numElements();
  const int nn = mesh.numNodes();
  const int dpn = dofsPerNode(field);
  const int nd = 4 * dpn;
  auto xe = elementCoords(mesh);
  Kokkos::View<double***, Kokkos::HostSpace> Ke("Ke", ne, nd, nd);
  Kokkos::View<double*, Kokkos::HostSpace> minDet("minDet", ne);
  double D[9];
  law.planeStrainMatrix(D);

  // Element stiffness: sum over Gauss points of B^T D B det(J) (B = grad N for the Laplacian).
  Kokkos::parallel_for(
      "plasticity::q1_stiffness", Kokkos::RangePolicy<ExecSpace>(0, ne), KOKKOS_LAMBDA(int e) {
        double x[8];
        for (int k = 0; k < 8; ++k) x[k] = xe(e, k);
        double detMin = 1e300;
        for (int gp = 0; gp < 4; ++gp) {
          const double xi = (gp % 2 ? kGauss : -kGauss), eta = (gp / 2 ? kGauss : -kGauss);
          double dN[4][2], N[4];
          const double det = q1Gradients(x, xi, eta, dN, N);
          detMin = det < detMin ? det : detMin;
          if (dpn == 1) {
            for (int a = 0; a < 4; ++a)
              for (int b = 0; b < 4; ++b)
                Ke(e, a, b) += (dN[a][0] * dN[b][0] + dN[a][1] * dN[b][1]) * det;
          } else {
            double Bm[3][8] = {};
            for (int a = 0; a < 4; ++a) {
              Bm[0][2 * a] = dN[a][0];
              Bm[1][2 * a + 1] = dN[a][1];
              Bm[2][2 * a] = dN[a][1];
              Bm[2][2 * a + 1] = dN[a][0];
            }
            double DB[3][8];
            for (int i = 0; i < 3; ++i)
              for (int j = 0; j < 8; ++j)
                DB[i][j] = D[3 * i] * Bm[0][j] + D[3 * i + 1] * Bm[1][j] + D[3 * i + 2] * Bm[2][j];
            for (int i = 0; i < 8; ++i)
              for (int j = 0; j < 8; ++j)
                Ke(e, i, j) +=
                    (Bm[0][i] * DB[0][j] + Bm[1][i] * DB[1][j] + Bm[2][i] * DB[2][j]) * det;
          }
        }
        // Corners too: a non-convex quadrilateral can have positive Gauss-point Jacobians.
        for (int c = 0; c < 4; ++c) {
          double dN[4][2], N[4];
          const double det =
              q1Gradients(x, c == 1 || c == 2 ? 1.0 : -1.0, c >= 2 ? 1.0 : -1.0, dN, N);
          detMin = det < detMin ? det : detMin;
        }
        minDet(e) = detMin;
      });
  checkJacobians(minDet);

  // Sparsity pattern: node-to-node adjacency through elements, expanded to dofs.
  std::vector<std::vector<int>> adj(nn);
  for (int e = 0; e < ne; ++e)
    for (int a = 0; a < 4; ++a)
      for (int b = 0; b < 4; ++b) adj[mesh.quads[4 * e + a]].push_back(mesh.quads[4 * e + b]);
  tfeti::CsrMatrix K;
  K.rows = K.cols = nn * dpn;
  K.rowPtr.assign(K.rows + 1, 0);
  for (int n = 0; n < nn; ++n) {
    auto& a = adj[n];
    std::sort(a.begin(), a.end());
    a.erase(std::unique(a.begin(), a.end()), a.end());
    for (int c = 0; c < dpn; ++c) {
      for (int m : a)
        for (int d = 0; d < dpn; ++d) K.colInd.push_back(m * dpn + d);
      K.rowPtr[n * dpn + c + 1] = static_cast<int>(K.colInd.size());
    }
  }
  K.values.assign(K.colInd.size(), 0.0);

  // Scatter: each element adds its block into the pattern; atomics keep this correct should the
  // execution space ever be threaded.
  Kokkos::View<double*, Kokkos::HostSpace, Kokkos::MemoryTraits<Kokkos::Unmanaged>> vals(
      K.values.data(), K.values.size());
  const tfeti::CsrMatrix& Kc = K;
  Kokkos::parallel_for("plasticity::q1_scatter", Kokkos::RangePolicy<ExecSpace>(0, ne), [&](int e) {
    for (int a = 0; a < 4; ++a)
      for (int c = 0; c < dpn; ++c) {
        const int row = mesh.quads[4 * e + a] * dpn + c;
        for (int b = 0; b < 4; ++b)
          for (int d = 0; d < dpn; ++d) {
            const long k = Kc.find(row, mesh.quads[4 * e + b] * dpn + d);
            Kokkos::atomic_add(&vals(k), Ke(e, a * dpn + c, b * dpn + d));
          }
      }
  });
  return K;
}

std::vector<double> assembleBodyLoad(const QuadMesh& mesh, Field field, const double* source) {
  const int dpn = dofsPerNode(field);
  std::vector<double> perElement(static_cast<std::size_t>(mesh.numElements()) * dpn);
  for (std::size_t k = 0; k < perElement.size(); ++k) perElement[k] = source[k % dpn];
  return assembleBodyLoad(mesh, field, perElement);
}

std::vector<double> assembleBodyLoad(const QuadMesh& mesh, Field field,
                                     const std::vector<double>& elementSource) {
  const int ne = mesh.numElements();
  const int dpn = dofsPerNode(field);
  if (elementSource.size() != static_cast<std::size_t>(ne) * dpn)
    throw std::invalid_argument("assembleBodyLoad: " + std::to_string(elementSource.size()) +
                                " source values for " + std::to_string(ne) + " elements");
  auto xe = elementCoords(mesh);
  Kokkos::View<double*, Kokkos::HostSpace> w("nodalWeights", 4 * ne);
  Kokkos::parallel_for(
      "plasticity::q1_load", Kokkos::RangePolicy<ExecSpace>(0, ne), KOKKOS_LAMBDA(int e) {
        double x[8];
        for (int k = 0; k < 8; ++k) x[k] = xe(e, k);
        for (int gp = 0; gp < 4; ++gp) {
          const double xi = (gp % 2 ? kGauss : -kGauss), eta = (gp / 2 ? kGauss : -kGauss);
          double dN[4][2], N[4];
          const double det = q1Gradients(x, xi, eta, dN, N);
          for (int a = 0; a < 4; ++a) w(4 * e + a) += N[a] * det;
        }
      });
  std::vector<double> f(static_cast<std::size_t>(mesh.numNodes()) * dpn, 0.0);
  for (int e = 0; e < ne; ++e)
    for (int a = 0; a < 4; ++a)
      for (int c = 0; c < dpn; ++c)
        f[mesh.quads[4 * e + a] * dpn + c] += w(4 * e + a) * elementSource[e * dpn + c];
  return f;
}

}  // namespace plasticity
