#pragma once
// Meshes of the unit square for the element tests, built on a lattice of nodes: the (n+1)^2
// element vertices for linear elements, (2n+1)^2 nodes (vertices, edge mid-nodes, quad centres)
// for quadratic ones. Triangles split each quad cell along alternating diagonals; a diagonal's
// mid-node is the cell's centre lattice node. Vertices come from a caller-supplied map of the
// regular grid, so the quadrilaterals are general (non-parallelogram) while the domain stays
// the unit square.
#include <cmath>
#include <functional>
#include <vector>

#include "plasticity_Elements.hpp"

namespace plasticity_test {

using plasticity::ElementMesh;
using plasticity::ElementType;

// Position of grid vertex (i, j), 0 <= i, j <= n.
using VertexMap = std::function<void(int i, int j, int n, double& x, double& y)>;

struct LatticeMesh {
  ElementMesh mesh;
  int n = 0;     // cells per side
  int side = 0;  // lattice nodes per side
  bool onBoundary(int node) const {
    const int I = node % side, J = node / side;
    return I == 0 || J == 0 || I == side - 1 || J == side - 1;
  }
  // Edges along side k (0: y = 0, 1: x = 1, 2: y = 1, 3: x = 0), nodesPerEdge nodes each.
  std::vector<int> sideEdges(int k) const {
    const int s = (side - 1) / n;
    auto id = [&](int t) {
      const int along = t, last = side - 1;
      return k == 0   ? along
             : k == 1 ? along * side + last
             : k == 2 ? last * side + along
                      : along * side;
    };
    std::vector<int> edges;
    for (int c = 0; c < n; ++c) {
      edges.push_back(id(s * c));
      edges.push_back(id(s * (c + 1)));
      if (s == 2) edges.push_back(id(s * c + 1));
    }
    return edges;
  }
};

// Deterministic pseudo-random numbers in [-1, 1] (no dependence on the library's generator).
inline double jitter(int i, int j, int salt) {
  unsigned h = 2166136261u;
  for (int v : {i, j, salt}) h = (h ^ static_cast<unsigned>(v + 1013)) * 16777619u;
  h ^= h >> 13, h *= 0x5bd1e995u, h ^= h >> 15;
  return (h % 20001u) / 10000.0 - 1.0;
}

// Vertices moved at random by up to `amount` times the spacing; boundary vertices slide along
// their side and the corners stay.
inline VertexMap randomVertices(double amount) {
  return [amount](int i, int j, int n, double& x, double& y) {
    const double h = 1.0 / n;
    x = i * h, y = j * h;
    if (i > 0 && i < n) x += amount * h * jitter(i, j, 1);
    if (j > 0 && j < n) y += amount * h * jitter(i, j, 2);
  };
}

// A smooth map of the unit square onto itself: a mesh family of fixed shape quality, as a
// convergence study needs.
inline VertexMap smoothVertices(double amount) {
  return [amount](int i, int j, int n, double& x, double& y) {
    const double pi = 3.14159265358979323846;
    const double u = double(i) / n, v = double(j) / n;
    x = u + amount * std::sin(pi * u) * std::sin(2 * pi * v);
    y = v + amount * std::sin(2 * pi * u) * std::sin(pi * v);
  };
}

// The mesh. Non-vertex nodes sit at the middle of straight edges (Quad9 centres at the mean of
// the corners: bilinear geometry, exactly representing quadratic fields); with curve > 0 they
// are then moved by up to curve times the lattice spacing (along the side on the boundary), so
// that quadratic elements have curved interior edges.
inline LatticeMesh latticeMesh(ElementType type, int n, const VertexMap& vertex,
                               double curve = 0.0) {
  LatticeMesh L;
  L.n = n;
  const int s = plasticity::isQuadratic(type) ? 2 : 1;
  L.side = s * n + 1;
  ElementMesh& m = L.mesh;
  m.type = type;
  m.coords.assign(2 * L.side * L.side, 0.0);
  auto id = [&](int I, int J) { return J * L.side + I; };
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i)
      vertex(i, j, n, m.coords[2 * id(s * i, s * j)], m.coords[2 * id(s * i, s * j) + 1]);
  auto setMean = [&](int target, std::vector<int> from) {
    for (int c = 0; c < 2; ++c) {
      double sum = 0;
      for (int f : from) sum += m.coords[2 * f + c];
      m.coords[2 * target + c] = sum / from.size();
    }
  };
  // Lattice node halfway between lattice nodes (I0, J0) and (I1, J1).
  auto mid = [&](int I0, int J0, int I1, int J1) {
    const int k = id((I0 + I1) / 2, (J0 + J1) / 2);
    setMean(k, {id(I0, J0), id(I1, J1)});
    return k;
  };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const int I = s * i, J = s * j;
      // Corners counter-clockwise, as lattice coordinates.
      const int c[4][2] = {{I, J}, {I + s, J}, {I + s, J + s}, {I, J + s}};
      std::vector<std::vector<int>> cells;  // corner indices into c, per element
      if (type == ElementType::Quad4 || type == ElementType::Quad9) {
        cells = {{0, 1, 2, 3}};
      } else if ((i + j) % 2 == 0) {
        cells = {{0, 1, 2}, {0, 2, 3}};
      } else {
        cells = {{0, 1, 3}, {1, 2, 3}};
      }
      for (const auto& cell : cells) {
        const int nc = static_cast<int>(cell.size());
        for (int a : cell) m.connectivity.push_back(id(c[a][0], c[a][1]));
        if (s == 2)
          for (int k = 0; k < nc; ++k) {
            const int* p = c[cell[k]];
            const int* q = c[cell[(k + 1) % nc]];
            m.connectivity.push_back(mid(p[0], p[1], q[0], q[1]));
          }
        if (type == ElementType::Quad9) {
          const int centre = id(I + 1, J + 1);
          setMean(centre, {id(I, J), id(I + 2, J), id(I + 2, J + 2), id(I, J + 2)});
          m.connectivity.push_back(centre);
        }
      }
    }
  if (curve > 0 && s == 2) {
    const double h = 1.0 / (2 * n);
    for (int J = 0; J < L.side; ++J)
      for (int I = 0; I < L.side; ++I) {
        if (I % 2 == 0 && J % 2 == 0) continue;  // vertices stay
        const int k = id(I, J);
        const bool fixX = I == 0 || I == L.side - 1, fixY = J == 0 || J == L.side - 1;
        if (!fixX) m.coords[2 * k] += curve * h * jitter(I, J, 3);
        if (!fixY) m.coords[2 * k + 1] += curve * h * jitter(I, J, 4);
      }
  }
  return L;
}

}  // namespace plasticity_test
