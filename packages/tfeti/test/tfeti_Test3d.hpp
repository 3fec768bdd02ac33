#pragma once
// Test-only 3D finite elements for the tfeti unit tests: Tet4 (exact integration) and Hex8
// (2x2x2 Gauss) stiffness matrices of the Laplacian and of isotropic linear elasticity, a
// constant body load, and a box of hexahedra (or of tetrahedra, six per cube along the main
// diagonal: a conforming split) torn into a grid of subdomains, and contact rows of a rigid floor
// under it. The production 3D kernels live in the plasticity package; these are here so that the
// FETI tests do not depend on them.
#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include <Tpetra_Core.hpp>

#include "tfeti_CsrMatrix.hpp"
#include "tfeti_FetiSolver.hpp"
#include "tfeti_LocalSolver.hpp"
#include "tfeti_SubdomainDistribution.hpp"
#include "tfeti_SubdomainMesh.hpp"
#include "tfeti_TestHelpers.hpp"

namespace tfeti_test {

struct Material3d {
  int dofsPerNode = 1;  // 1: -Laplace u = f; 3: elasticity
  double E = 1.0, nu = 0.3;
};

namespace detail {

// Element matrix from the shape function gradients at one point (G: nodes x 3), weight w.
inline void addPointContribution(const Material3d& mat, const std::vector<double>& G, int nn,
                                 double w, std::vector<double>& Ke) {
  const int dpn = mat.dofsPerNode, m = nn * dpn;
  if (dpn == 1) {
    for (int a = 0; a < nn; ++a)
      for (int b = 0; b < nn; ++b) {
        double s = 0.0;
        for (int c = 0; c < 3; ++c) s += G[3 * a + c] * G[3 * b + c];
        Ke[b * m + a] += w * s;
      }
    return;
  }
  const double lam = mat.E * mat.nu / ((1 + mat.nu) * (1 - 2 * mat.nu));
  const double mu = mat.E / (2 * (1 + mat.nu));
  // K_ab(i,j) = lam dNa_i dNb_j + mu (dNa_j dNb_i + delta_ij dNa . dNb)
  for (int a = 0; a < nn; ++a)
    for (int b = 0; b < nn; ++b) {
      double dot = 0.0;
      for (int c = 0; c < 3; ++c) dot += G[3 * a + c] * G[3 * b + c];
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
          const double v = lam * G[3 * a + i] * G[3 * b + j] +
                           mu * (G[3 * a + j] * G[3 * b + i] + (i == j ? dot : 0.0));
          Ke[(3 * b + j) * m + 3 * a + i] += w * v;
        }
    }
}

// Inverse transpose of the 3x3 Jacobian J (J[i][j] = dx_i / dxi_j) applied to reference
// gradients; returns det J.
inline double physicalGradients(const std::vector<double>& x, const std::vector<double>& dN, int nn,
                                std::vector<double>& G) {
  double J[3][3] = {};
  for (int a = 0; a < nn; ++a)
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) J[i][j] += x[3 * a + i] * dN[3 * a + j];
  const double det = J[0][0] * (J[1][1] * J[2][2] - J[1][2] * J[2][1]) -
                     J[0][1] * (J[1][0] * J[2][2] - J[1][2] * J[2][0]) +
                     J[0][2] * (J[1][0] * J[2][1] - J[1][1] * J[2][0]);
  if (!(det > 0.0)) throw std::invalid_argument("test element: non-positive Jacobian");
  double inv[3][3];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      const int i1 = (j + 1) % 3, i2 = (j + 2) % 3, j1 = (i + 1) % 3, j2 = (i + 2) % 3;
      inv[i][j] = (J[i1][j1] * J[i2][j2] - J[i1][j2] * J[i2][j1]) / det;
    }
  G.assign(3 * nn, 0.0);
  // dN/dx_k = sum_j dN/dxi_j (J^{-1})_{jk}
  for (int a = 0; a < nn; ++a)
    for (int k = 0; k < 3; ++k)
      for (int j = 0; j < 3; ++j) G[3 * a + k] += dN[3 * a + j] * inv[j][k];
  return det;
}

}  // namespace detail

// Element stiffness (column-major) and volume of a Tet4 (4 nodes) or Hex8 (8 nodes, VTK order).
inline std::vector<double> elementStiffness3d(const std::vector<double>& x, const Material3d& mat,
                                              double* volume = nullptr) {
  const int nn = static_cast<int>(x.size() / 3), m = nn * mat.dofsPerNode;
  std::vector<double> Ke(static_cast<std::size_t>(m) * m, 0.0), G;
  double vol = 0.0;
  if (nn == 4) {
    const std::vector<double> dN = {-1, -1, -1, 1, 0, 0, 0, 1, 0, 0, 0, 1};
    const double det = detail::physicalGradients(x, dN, 4, G);
    detail::addPointContribution(mat, G, 4, det / 6.0, Ke);
    vol = det / 6.0;
  } else if (nn == 8) {
    static const int sx[8] = {-1, 1, 1, -1, -1, 1, 1, -1}, sy[8] = {-1, -1, 1, 1, -1, -1, 1, 1},
                     sz[8] = {-1, -1, -1, -1, 1, 1, 1, 1};
    const double g = 1.0 / std::sqrt(3.0);
    for (int q = 0; q < 8; ++q) {
      const double xi = g * sx[q], eta = g * sy[q], zeta = g * sz[q];
      std::vector<double> dN(24);
      for (int a = 0; a < 8; ++a) {
        dN[3 * a] = 0.125 * sx[a] * (1 + eta * sy[a]) * (1 + zeta * sz[a]);
        dN[3 * a + 1] = 0.125 * sy[a] * (1 + xi * sx[a]) * (1 + zeta * sz[a]);
        dN[3 * a + 2] = 0.125 * sz[a] * (1 + xi * sx[a]) * (1 + eta * sy[a]);
      }
      const double det = detail::physicalGradients(x, dN, 8, G);
      detail::addPointContribution(mat, G, 8, det, Ke);
      vol += det;
    }
  } else {
    throw std::invalid_argument("test element: " + std::to_string(nn) + " nodes");
  }
  if (volume) *volume = vol;
  return Ke;
}

// K and the load of a constant body force (per unit volume, dofsPerNode components; lumped
// equally on the element's nodes, which is exact for Tet4 and for parallelepiped Hex8).
inline void assemble3d(const std::vector<double>& coords, const tfeti::ElementConnectivity& els,
                       const Material3d& mat, const std::vector<double>& force, tfeti::CsrMatrix& K,
                       std::vector<double>& f) {
  const int dpn = mat.dofsPerNode, n = static_cast<int>(coords.size() / 3) * dpn;
  std::vector<int> ri, ci;
  std::vector<double> v;
  f.assign(n, 0.0);
  for (int e = 0; e < els.size(); ++e) {
    std::vector<int> nodes(els.nodes.begin() + els.offsets[e],
                           els.nodes.begin() + els.offsets[e + 1]);
    const int nn = static_cast<int>(nodes.size()), m = nn * dpn;
    std::vector<double> x;
    for (int a : nodes)
      for (int c = 0; c < 3; ++c) x.push_back(coords[3 * a + c]);
    double vol = 0.0;
    const std::vector<double> Ke = elementStiffness3d(x, mat, &vol);
    for (int a = 0; a < m; ++a) {
      f[nodes[a / dpn] * dpn + a % dpn] += vol / nn * force[a % dpn];
      for (int b = 0; b < m; ++b) {
        ri.push_back(nodes[a / dpn] * dpn + a % dpn);
        ci.push_back(nodes[b / dpn] * dpn + b % dpn);
        v.push_back(Ke[static_cast<std::size_t>(b) * m + a]);
      }
    }
  }
  K = tfeti::csrFromTriplets(n, n, ri, ci, v);
}

// The unit-spaced box [0, NX] x [0, NY] x [0, NZ] of elements (NX = sx * ex, ...) torn into
// sx x sy x sz subdomains of ex x ey x ez cubes each (x fastest), cubes split into six
// tetrahedra when tets is set. Dirichlet nodes: x = 0.
class Box3d {
 public:
  Box3d(int sx, int sy, int sz, int ex, int ey, int ez, bool tets)
      : s_{sx, sy, sz}, e_{ex, ey, ez}, tets_(tets) {}
  int numSubdomains() const { return s_[0] * s_[1] * s_[2]; }
  tfeti::SubdomainMesh subdomain(int s) const {
    const int i = s % s_[0], j = (s / s_[0]) % s_[1], k = s / (s_[0] * s_[1]);
    tfeti::SubdomainMesh m = block({i * e_[0], j * e_[1], k * e_[2]}, e_);
    m.id = s;
    return m;
  }
  tfeti::SubdomainMesh wholeMesh() const {
    tfeti::SubdomainMesh m = block({0, 0, 0}, {s_[0] * e_[0], s_[1] * e_[1], s_[2] * e_[2]});
    m.id = -1;
    return m;
  }

 private:
  tfeti::SubdomainMesh block(std::array<int, 3> o, std::array<int, 3> n) const {
    const int NX = s_[0] * e_[0] + 1, NY = s_[1] * e_[1] + 1;
    tfeti::SubdomainMesh m;
    m.dim = 3;
    const auto local = [&](int i, int j, int k) { return (k * (n[1] + 1) + j) * (n[0] + 1) + i; };
    for (int k = 0; k <= n[2]; ++k)
      for (int j = 0; j <= n[1]; ++j)
        for (int i = 0; i <= n[0]; ++i) {
          m.coords.insert(m.coords.end(), {double(o[0] + i), double(o[1] + j), double(o[2] + k)});
          m.globalNode.push_back((static_cast<tfeti::GO>(o[2] + k) * NY + o[1] + j) * NX + o[0] +
                                 i);
          if (o[0] + i == 0) m.dirichletNodes.push_back(local(i, j, k));
          const bool face = i == 0 || j == 0 || k == 0 || i == n[0] || j == n[1] || k == n[2];
          if (face) m.interfaceCandidates.push_back(local(i, j, k));
        }
    for (int k = 0; k < n[2]; ++k)
      for (int j = 0; j < n[1]; ++j)
        for (int i = 0; i < n[0]; ++i) {
          // Corner c = bits (x, y, z) of the cube.
          const auto corner = [&](int c) {
            return local(i + (c & 1), j + (c >> 1 & 1), k + (c >> 2));
          };
          if (!tets_) {
            m.elements.add({corner(0), corner(1), corner(3), corner(2), corner(4), corner(5),
                            corner(7), corner(6)});
            continue;
          }
          // Six tetrahedra along the diagonal 0 -> 7, one per order of the axes.
          static const int axes[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2},
                                         {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
          for (const auto& a : axes) {
            const int c1 = 1 << a[0], c2 = c1 | 1 << a[1];
            std::vector<int> t = {corner(0), corner(c1), corner(c2), corner(7)};
            // Positive orientation: swap two nodes when the axis order is odd.
            const bool odd =
                (a[0] == 0 && a[1] == 2) || (a[0] == 1 && a[1] == 0) || (a[0] == 2 && a[1] == 1);
            if (odd) std::swap(t[1], t[2]);
            m.elements.add(t);
          }
        }
    return m;
  }
  std::array<int, 3> s_, e_;
  bool tets_;
};

// Direct solve of the untorn problem with the Dirichlet dofs (x = 0) eliminated, by CHOLMOD;
// indexed by untorn dof.
inline std::vector<double> referenceSolution3d(const Box3d& box, const Material3d& mat,
                                               const std::vector<double>& force) {
  const tfeti::SubdomainMesh whole = box.wholeMesh();
  tfeti::CsrMatrix K;
  std::vector<double> f;
  assemble3d(whole.coords, whole.elements, mat, force, K, f);
  return solveWithDirichlet(std::move(K), std::move(f), whole.dirichletDofs(mat.dofsPerNode));
}

// The subdomains of `box` on this rank (increasing id), assembled with the kernels above under
// the constant body load `force` (one value per dof of a node).
inline std::vector<tfeti::SubdomainData> localBoxSubdomains(const Box3d& box, const Material3d& mat,
                                                            const std::vector<double>& force,
                                                            const tfeti::Comm& comm) {
  std::vector<tfeti::SubdomainData> local;
  for (int s : tfeti::subdomainsOfRank(comm.getRank(), box.numSubdomains(), comm.getSize())) {
    tfeti::SubdomainData d;
    d.mesh = box.subdomain(s);
    d.dofsPerNode = mat.dofsPerNode;
    assemble3d(d.mesh.coords, d.mesh.elements, mat, force, d.K, d.f);
    local.push_back(std::move(d));
  }
  return local;
}

// A rigid floor under a box: coef(x) u_z <= gap(x) (coef -1 unless given) for each node of the
// bottom z = 0 at x >= xMin, on the first subdomain that holds it, keyed by the node where
// `keyed` (rank 0 passes them all).
template <class Gap, class Coef = double (*)(double)>
std::vector<tfeti::InequalityRow> floorRows(
    const Box3d& box, const Gap& gap, double xMin, bool keyed,
    const Coef& coef = [](double) { return -1.0; }) {
  std::vector<tfeti::InequalityRow> rows;
  if (Tpetra::getDefaultComm()->getRank() != 0) return rows;
  std::vector<long long> seen;
  for (int sub = 0; sub < box.numSubdomains(); ++sub) {
    const tfeti::SubdomainMesh m = box.subdomain(sub);
    for (int n = 0; n < m.numNodes(); ++n) {
      const long long node = m.globalNode[n];
      const double x = m.coords[3 * n];
      if (m.coords[3 * n + 2] != 0.0 || x < xMin ||
          std::find(seen.begin(), seen.end(), node) != seen.end())
        continue;
      seen.push_back(node);
      tfeti::InequalityRow r;
      r.entries = {{sub, 3 * n + 2, coef(x)}};
      r.gap = gap(x);
      r.key = keyed ? node : -1;
      rows.push_back(r);
    }
  }
  return rows;
}

}  // namespace tfeti_test
