#include "plasticity_Q1Assembly.hpp"

#include <Kokkos_Core.hpp>

#include <algorithm>
#include <stdexcept>
#include <string>

namespace plasticity {
namespace {

using ExecSpace = Kokkos::DefaultHostExecutionSpace;
constexpr double kGauss = 0.57735026918962576451;  // 1/sqrt(3)

// The Q1 element in D dimensions: N = 2^D corners in VTK order, shape functions
// prod_d (1 + s_d p_d) / 2 with the corner's signs s, tensor 2-point Gauss rule.
template <int D>
struct Q1 {
  static constexpr int N = 1 << D;

  // The sign (-1 or +1) of corner a along an axis: (-,-), (+,-), (+,+), (-,+) in the plane,
  // the bottom face (z = -1) before the top one.
  KOKKOS_INLINE_FUNCTION static double sign(int a, int axis) {
    if (axis == 2) return a >= 4 ? 1.0 : -1.0;
    const int c = a % 4;
    return (axis == 0 ? (c == 1 || c == 2) : (c >= 2)) ? 1.0 : -1.0;
  }

  // Gauss point g (or corner g with at = 1) of the reference cell: its bit d is the sign along d.
  KOKKOS_INLINE_FUNCTION static void point(int g, double at, double p[D]) {
    for (int d = 0; d < D; ++d) p[d] = ((g >> d) & 1) ? at : -at;
  }

  // Shape functions and their x-gradients at the reference point p; returns det(J).
  KOKKOS_INLINE_FUNCTION static double gradients(const double* xe, const double p[D],
                                                 double dN[N][D], double Nv[N]) {
    double dP[N][D];
    for (int a = 0; a < N; ++a) {
      double f[D];
      for (int d = 0; d < D; ++d) f[d] = 0.5 * (1.0 + sign(a, d) * p[d]);
      Nv[a] = 1.0;
      for (int d = 0; d < D; ++d) Nv[a] *= f[d];
      for (int k = 0; k < D; ++k) {
        dP[a][k] = 0.5 * sign(a, k);
        for (int d = 0; d < D; ++d)
          if (d != k) dP[a][k] *= f[d];
      }
    }
    double J[D][D] = {};
    for (int a = 0; a < N; ++a)
      for (int i = 0; i < D; ++i)
        for (int k = 0; k < D; ++k) J[i][k] += xe[D * a + i] * dP[a][k];
    double inv[D][D], det;
    if constexpr (D == 2) {
      det = J[0][0] * J[1][1] - J[0][1] * J[1][0];
      inv[0][0] = J[1][1] / det, inv[0][1] = -J[0][1] / det;
      inv[1][0] = -J[1][0] / det, inv[1][1] = J[0][0] / det;
    } else {
      // Cofactors: inv = adj(J) / det(J).
      for (int i = 0; i < 3; ++i)
        for (int k = 0; k < 3; ++k) {
          const int i1 = (i + 1) % 3, i2 = (i + 2) % 3, k1 = (k + 1) % 3, k2 = (k + 2) % 3;
          inv[k][i] = J[i1][k1] * J[i2][k2] - J[i1][k2] * J[i2][k1];
        }
      det = J[0][0] * inv[0][0] + J[0][1] * inv[1][0] + J[0][2] * inv[2][0];
      for (int i = 0; i < 3; ++i)
        for (int k = 0; k < 3; ++k) inv[i][k] /= det;
    }
    for (int a = 0; a < N; ++a)
      for (int j = 0; j < D; ++j) {
        dN[a][j] = 0.0;
        for (int k = 0; k < D; ++k) dN[a][j] += dP[a][k] * inv[k][j];
      }
    return det;
  }
};

void checkMesh(const Q1Mesh& mesh) {
  if (mesh.dim != 2 && mesh.dim != 3)
    throw std::invalid_argument("Q1 assembly: dimension " + std::to_string(mesh.dim) +
                                " (2 or 3 expected)");
  if (mesh.coords.size() % mesh.dim != 0 || mesh.cells.size() % mesh.nodesPerCell() != 0)
    throw std::invalid_argument("Q1 assembly: " + std::to_string(mesh.coords.size()) +
                                " coordinates and " + std::to_string(mesh.cells.size()) +
                                " cell entries do not fit " + std::to_string(mesh.dim) +
                                "D cells of " + std::to_string(mesh.nodesPerCell()) + " nodes");
  for (std::size_t k = 0; k < mesh.cells.size(); ++k)
    if (mesh.cells[k] < 0 || mesh.cells[k] >= mesh.numNodes())
      throw std::invalid_argument(
          "Q1 assembly: element " + std::to_string(k / mesh.nodesPerCell()) + " refers to node " +
          std::to_string(mesh.cells[k]) + " of " + std::to_string(mesh.numNodes()));
}

// Element coordinates gathered into a View so that the kernels see plain arrays.
template <int D>
Kokkos::View<double**, Kokkos::HostSpace> elementCoords(const Q1Mesh& mesh) {
  const int ne = mesh.numElements();
  Kokkos::View<double**, Kokkos::HostSpace> xe("xe", ne, D * Q1<D>::N);
  for (int e = 0; e < ne; ++e)
    for (int a = 0; a < Q1<D>::N; ++a)
      for (int d = 0; d < D; ++d)
        xe(e, D * a + d) = mesh.coords[D * mesh.cells[Q1<D>::N * e + a] + d];
  return xe;
}

void checkJacobians(const Kokkos::View<double*, Kokkos::HostSpace>& minDet) {
  for (std::size_t e = 0; e < minDet.extent(0); ++e)
    if (!(minDet(e) > 0.0))
      throw std::runtime_error("element " + std::to_string(e) +
                               " is degenerate or inverted (Jacobian determinant " +
                               std::to_string(minDet(e)) + ")");
}

// Sparsity pattern: node-to-node adjacency through elements, expanded to dofs (a node's dofs
// are contiguous within each row).
tfeti::CsrMatrix pattern(const Q1Mesh& mesh, int dpn) {
  const int nn = mesh.numNodes(), npe = mesh.nodesPerCell();
  std::vector<std::vector<int>> adj(nn);
  for (int e = 0; e < mesh.numElements(); ++e)
    for (int a = 0; a < npe; ++a)
      for (int b = 0; b < npe; ++b) adj[mesh.cells[npe * e + a]].push_back(mesh.cells[npe * e + b]);
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
    std::vector<int>().swap(a);
  }
  K.values.assign(K.colInd.size(), 0.0);
  return K;
}

template <int D>
tfeti::CsrMatrix stiffness(const Q1Mesh& mesh, Field field, const ElasticLaw& law) {
  constexpr int N = Q1<D>::N;
  const int ne = mesh.numElements();
  const int dpn = dofsPerNode(field, D);
  const bool scalar = field == Field::Scalar;
  const double lambda = law.lambda(), mu = law.mu();
  auto xe = elementCoords<D>(mesh);
  Kokkos::View<double*, Kokkos::HostSpace> minDet("minDet", ne);
  tfeti::CsrMatrix K = pattern(mesh, dpn);
  Kokkos::View<double*, Kokkos::HostSpace, Kokkos::MemoryTraits<Kokkos::Unmanaged>> vals(
      K.values.data(), K.values.size());
  const tfeti::CsrMatrix& Kc = K;

  // Per element: A_ab^ij = sum over Gauss points of dN_a/dx_i dN_b/dx_j det(J). The Laplacian
  // is sum_i A_ab^ii; isotropic elasticity is K_(a,i),(b,j) = lambda A_ab^ij + mu A_ab^ji +
  // mu delta_ij sum_k A_ab^kk (B^T D B written out), the same in 2D (plane strain) and 3D.
  // Each element adds its block into the pattern as it goes (atomics keep this correct should
  // the execution space ever be threaded), so no element matrices are stored.
  Kokkos::parallel_for(
      "plasticity::q1_stiffness", Kokkos::RangePolicy<ExecSpace>(0, ne), [&](int e) {
        double x[D * N];
        for (int k = 0; k < D * N; ++k) x[k] = xe(e, k);
        double A[N][N][D][D] = {};
        double detMin = 1e300;
        for (int gp = 0; gp < N; ++gp) {
          double p[D], dN[N][D], Nv[N];
          Q1<D>::point(gp, kGauss, p);
          const double det = Q1<D>::gradients(x, p, dN, Nv);
          detMin = det < detMin ? det : detMin;
          for (int a = 0; a < N; ++a)
            for (int b = 0; b < N; ++b)
              for (int i = 0; i < D; ++i)
                for (int j = 0; j < D; ++j) A[a][b][i][j] += dN[a][i] * dN[b][j] * det;
        }
        // Corners too: a non-convex cell can have positive Gauss-point Jacobians.
        for (int c = 0; c < N; ++c) {
          double p[D], dN[N][D], Nv[N];
          Q1<D>::point(c, 1.0, p);
          const double det = Q1<D>::gradients(x, p, dN, Nv);
          detMin = det < detMin ? det : detMin;
        }
        minDet(e) = detMin;
        for (int a = 0; a < N; ++a)
          for (int b = 0; b < N; ++b) {
            double trace = 0.0;
            for (int k = 0; k < D; ++k) trace += A[a][b][k][k];
            const int nodeA = mesh.cells[N * e + a], nodeB = mesh.cells[N * e + b];
            for (int i = 0; i < dpn; ++i) {
              // Columns of node b are contiguous in the row: one search per node pair.
              const long k0 = Kc.find(nodeA * dpn + i, nodeB * dpn);
              for (int j = 0; j < dpn; ++j) {
                const double v = scalar ? trace
                                        : lambda * A[a][b][i][j] + mu * A[a][b][j][i] +
                                              (i == j ? mu * trace : 0.0);
                Kokkos::atomic_add(&vals(k0 + j), v);
              }
            }
          }
      });
  checkJacobians(minDet);
  return K;
}

template <int D>
std::vector<double> bodyLoad(const Q1Mesh& mesh, Field field,
                             const std::vector<double>& elementSource) {
  constexpr int N = Q1<D>::N;
  const int ne = mesh.numElements();
  const int dpn = dofsPerNode(field, D);
  auto xe = elementCoords<D>(mesh);
  Kokkos::View<double**, Kokkos::HostSpace> w("nodalWeights", ne, N);
  Kokkos::parallel_for(
      "plasticity::q1_load", Kokkos::RangePolicy<ExecSpace>(0, ne), KOKKOS_LAMBDA(int e) {
        double x[D * N];
        for (int k = 0; k < D * N; ++k) x[k] = xe(e, k);
        for (int gp = 0; gp < N; ++gp) {
          double p[D], dN[N][D], Nv[N];
          Q1<D>::point(gp, kGauss, p);
          const double det = Q1<D>::gradients(x, p, dN, Nv);
          for (int a = 0; a < N; ++a) w(e, a) += Nv[a] * det;
        }
      });
  std::vector<double> f(static_cast<std::size_t>(mesh.numNodes()) * dpn, 0.0);
  for (int e = 0; e < ne; ++e)
    for (int a = 0; a < N; ++a)
      for (int c = 0; c < dpn; ++c)
        f[mesh.cells[N * e + a] * dpn + c] += w(e, a) * elementSource[e * dpn + c];
  return f;
}

}  // namespace

tfeti::CsrMatrix assembleStiffness(const Q1Mesh& mesh, Field field, const ElasticLaw& law) {
  checkMesh(mesh);
  return mesh.dim == 2 ? stiffness<2>(mesh, field, law) : stiffness<3>(mesh, field, law);
}

std::vector<double> assembleBodyLoad(const Q1Mesh& mesh, Field field, const double* source) {
  checkMesh(mesh);
  const int dpn = dofsPerNode(field, mesh.dim);
  std::vector<double> perElement(static_cast<std::size_t>(mesh.numElements()) * dpn);
  for (std::size_t k = 0; k < perElement.size(); ++k) perElement[k] = source[k % dpn];
  return assembleBodyLoad(mesh, field, perElement);
}

std::vector<double> assembleBodyLoad(const Q1Mesh& mesh, Field field,
                                     const std::vector<double>& elementSource) {
  checkMesh(mesh);
  const int ne = mesh.numElements();
  const int dpn = dofsPerNode(field, mesh.dim);
  if (elementSource.size() != static_cast<std::size_t>(ne) * dpn)
    throw std::invalid_argument("assembleBodyLoad: " + std::to_string(elementSource.size()) +
                                " source values for " + std::to_string(ne) + " elements");
  return mesh.dim == 2 ? bodyLoad<2>(mesh, field, elementSource)
                       : bodyLoad<3>(mesh, field, elementSource);
}

}  // namespace plasticity
