#pragma once
// Meshes of the unit cube for the 3D element tests, on a lattice of (s n + 1)^3 nodes (s = 1 for
// linear, 2 for quadratic elements). Hexahedra fill each cell; tetrahedra split each cell into
// the six Kuhn tetrahedra around its main diagonal (conforming across cells), every node placed
// through the element's reference node positions, so the node ordering under test is exactly
// the one plasticity_ElementTypes.hpp documents. Vertices come from a caller-supplied map of the
// regular grid; non-vertex nodes sit at the mean of the vertices of their edge, face or cell
// (trilinear hexahedra), and tetrahedra's mid nodes at the middle of their (straight) edges, as
// in the 2D test meshes.
#include <array>
#include <cmath>
#include <functional>
#include <vector>

#include "plasticity_ElementTestMeshes.hpp"
#include "plasticity_Elements.hpp"

namespace plasticity_test {

// Position of grid vertex (i, j, k), 0 <= i, j, k <= n.
using VertexMap3 = std::function<void(int i, int j, int k, int n, double x[3])>;

struct CubeMesh {
  ElementMesh mesh;
  int n = 0, side = 0;  // cells and lattice nodes per side
  int id(int I, int J, int K) const { return (K * side + J) * side + I; }
  bool onBoundary(int node) const {
    const int I = node % side, J = (node / side) % side, K = node / (side * side);
    for (int v : {I, J, K})
      if (v == 0 || v == side - 1) return true;
    return false;
  }
  // Faces on the cube side `axis` = 0 or 1 (x_axis = 0 or 1), nodesPerFace nodes each, in the
  // face type's node order.
  std::vector<int> sideFaces(int axis, int value) const;
};

// Vertices moved at random by up to `amount` times the spacing; boundary vertices stay on their
// faces (only the tangential coordinates move).
inline VertexMap3 randomVertices3(double amount) {
  return [amount](int i, int j, int k, int n, double x[3]) {
    const double h = 1.0 / n;
    const int ijk[3] = {i, j, k};
    for (int c = 0; c < 3; ++c) {
      x[c] = ijk[c] * h;
      if (ijk[c] > 0 && ijk[c] < n) x[c] += amount * h * jitter(i + 97 * k, j, c + 1);
    }
  };
}

// A smooth map of the unit cube onto itself (fixed shape quality under refinement).
inline VertexMap3 smoothVertices3(double amount) {
  return [amount](int i, int j, int k, int n, double x[3]) {
    const double pi = 3.14159265358979323846;
    const double u[3] = {double(i) / n, double(j) / n, double(k) / n};
    for (int c = 0; c < 3; ++c)
      x[c] = u[c] + amount * std::sin(pi * u[c]) * std::sin(2 * pi * u[(c + 1) % 3]) *
                        std::cos(pi * u[(c + 2) % 3]);
  };
}

inline CubeMesh cubeMesh(ElementType type, int n, const VertexMap3& vertex) {
  const plasticity::ElementInfo info = plasticity::elementInfo(type);
  const int s = info.order;
  CubeMesh C;
  C.n = n;
  C.side = s * n + 1;
  ElementMesh& m = C.mesh;
  m.type = type;
  m.coords.assign(3 * static_cast<std::size_t>(C.side) * C.side * C.side, 0.0);
  // Vertices, then every other lattice node as the mean of the vertices of the smallest lattice
  // box holding it (its edge, face or cell).
  for (int k = 0; k <= n; ++k)
    for (int j = 0; j <= n; ++j)
      for (int i = 0; i <= n; ++i) vertex(i, j, k, n, &m.coords[3 * C.id(s * i, s * j, s * k)]);
  if (s == 2)
    for (int K = 0; K < C.side; ++K)
      for (int J = 0; J < C.side; ++J)
        for (int I = 0; I < C.side; ++I) {
          if (I % 2 == 0 && J % 2 == 0 && K % 2 == 0) continue;
          const int lo[3] = {I - I % 2, J - J % 2, K - K % 2};
          const int hi[3] = {I + I % 2, J + J % 2, K + K % 2};
          double sum[3] = {0, 0, 0};
          int count = 0;
          for (int c = 0; c < 8; ++c) {
            const int a = c & 1 ? hi[0] : lo[0], b = c & 2 ? hi[1] : lo[1],
                      d = c & 4 ? hi[2] : lo[2];
            for (int x = 0; x < 3; ++x) sum[x] += m.coords[3 * C.id(a, b, d) + x];
            ++count;
          }
          for (int x = 0; x < 3; ++x) m.coords[3 * C.id(I, J, K) + x] = sum[x] / count;
        }
  // Elements: per cell, the corner positions (in cell units) of each element, then each node at
  // the affine image of its reference position (tetrahedra) or at its reference position
  // scaled into the cell (hexahedra).
  const int npe = info.nodes;
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        auto addNode = [&](const double p[3]) {  // p in cell units, multiples of 1/2
          m.connectivity.push_back(C.id(static_cast<int>(std::lround(s * (i + p[0]))),
                                        static_cast<int>(std::lround(s * (j + p[1]))),
                                        static_cast<int>(std::lround(s * (k + p[2])))));
        };
        if (!info.simplex) {
          for (int a = 0; a < npe; ++a) {
            double xi[3] = {0, 0, 0}, p[3];
            plasticity::referenceNode(type, a, xi);
            for (int c = 0; c < 3; ++c) p[c] = 0.5 * (xi[c] + 1);
            addNode(p);
          }
          continue;
        }
        const int perms[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
        for (const auto& pm : perms) {
          std::array<std::array<double, 3>, 4> c{};  // the path 0 -> e_p0 -> + e_p1 -> (1,1,1)
          for (int v = 1; v < 4; ++v) {
            c[v] = c[v - 1];
            c[v][pm[v - 1]] = 1;
          }
          // Right-handed: swap two corners when the reference map would invert.
          double d[3][3];
          for (int r = 0; r < 3; ++r)
            for (int x = 0; x < 3; ++x) d[r][x] = c[r + 1][x] - c[0][x];
          const double det = d[0][0] * (d[1][1] * d[2][2] - d[1][2] * d[2][1]) -
                             d[0][1] * (d[1][0] * d[2][2] - d[1][2] * d[2][0]) +
                             d[0][2] * (d[1][0] * d[2][1] - d[1][1] * d[2][0]);
          if (det < 0) std::swap(c[1], c[2]);
          for (int a = 0; a < npe; ++a) {
            double xi[3] = {0, 0, 0}, p[3];
            plasticity::referenceNode(type, a, xi);
            const double L[4] = {1 - xi[0] - xi[1] - xi[2], xi[0], xi[1], xi[2]};
            for (int x = 0; x < 3; ++x)
              p[x] = L[0] * c[0][x] + L[1] * c[1][x] + L[2] * c[2][x] + L[3] * c[3][x];
            addNode(p);
          }
          // Straight edges: a diagonal's mid node is its midpoint, not the mean of the
          // (distorted, non-planar) face or cell around it.
          const int* en = &m.connectivity[m.connectivity.size() - npe];
          for (int a = info.corners; a < npe; ++a) {
            int p0, p1;
            plasticity::detail::simplexEdge(a - info.corners, p0, p1);
            for (int x = 0; x < 3; ++x)
              m.coords[3 * en[a] + x] = 0.5 * (m.coords[3 * en[p0] + x] + m.coords[3 * en[p1] + x]);
          }
        }
      }
  return C;
}

// The boundary faces on a cube side: the faces of the elements' own face lists (nodes of the
// face type, in the order the face type's reference positions give on the element's face).
inline std::vector<int> CubeMesh::sideFaces(int axis, int value) const {
  const ElementType t = mesh.type, ft = plasticity::faceType(t);
  const int npe = plasticity::nodesPerElement(t), npf = plasticity::nodesPerElement(ft);
  const double target = value ? 1.0 : 0.0;
  std::vector<int> out;
  // Faces of each element: reuse the reference-position rule the kernels use, by probing
  // which element nodes lie on the lattice plane; then order them as the face type wants by
  // mapping the face type's reference nodes through the element's reference map.
  for (int e = 0; e < mesh.numElements(); ++e) {
    const int* en = &mesh.connectivity[static_cast<std::size_t>(e) * npe];
    auto lattice = [&](int node) {
      return std::array<int, 3>{node % side, (node / side) % side, node / (side * side)};
    };
    std::vector<int> on;
    for (int a = 0; a < npe; ++a)
      if (lattice(en[a])[axis] == static_cast<int>(target) * (side - 1)) on.push_back(a);
    if (static_cast<int>(on.size()) != npf) continue;
    // Face corner candidates: the element corners among `on`, taken in a cyclic order around
    // the face (sorted by angle about their centroid in the lattice plane).
    std::vector<int> corners;
    for (int a : on)
      if (a < plasticity::cornersPerElement(t)) corners.push_back(a);
    double cen[2] = {0, 0};
    const int u = (axis + 1) % 3, v = (axis + 2) % 3;
    for (int a : corners) cen[0] += lattice(en[a])[u], cen[1] += lattice(en[a])[v];
    cen[0] /= corners.size(), cen[1] /= corners.size();
    std::sort(corners.begin(), corners.end(), [&](int a, int b) {
      return std::atan2(lattice(en[a])[v] - cen[1], lattice(en[a])[u] - cen[0]) <
             std::atan2(lattice(en[b])[v] - cen[1], lattice(en[b])[u] - cen[0]);
    });
    // Every face node at the lattice position its face reference coordinates give through the
    // bilinear (quad) or affine (triangle) map of the corners.
    const int nc = static_cast<int>(corners.size());
    for (int f = 0; f < npf; ++f) {
      double xi[3], N[plasticity::kMaxElementNodes],
          dN[plasticity::kMaxElementNodes][plasticity::kMaxDim];
      plasticity::referenceNode(ft, f, xi);
      plasticity::shapeFunctions(plasticity::elementInfo(ft).linear, xi, N, dN);
      double p[3] = {0, 0, 0};
      for (int c = 0; c < nc; ++c)
        for (int x = 0; x < 3; ++x) p[x] += N[c] * lattice(en[corners[c]])[x];
      out.push_back(id(static_cast<int>(std::lround(p[0])), static_cast<int>(std::lround(p[1])),
                       static_cast<int>(std::lround(p[2]))));
    }
  }
  return out;
}

}  // namespace plasticity_test
