#include "contact_SurfaceWeights.hpp"

#include <array>
#include <cmath>
#include <stdexcept>
#include <vector>

namespace contact {

namespace {

using Vec3 = std::array<double, 3>;

Vec3 point(const GmshMesh& mesh, int node) {
  Vec3 x{0.0, 0.0, 0.0};
  for (int c = 0; c < mesh.dim; ++c) x[c] = mesh.coords[mesh.dim * node + c];
  return x;
}

Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

double norm(const Vec3& a) {
  return std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
}

Vec3 minus(const Vec3& a, const Vec3& b) {
  return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}

// A linear triangle: a third of its area to each corner.
void addTriangle(const GmshMesh& mesh, int a, int b, int c, std::map<int, double>& w) {
  const Vec3 xa = point(mesh, a);
  const double area = 0.5 * norm(cross(minus(point(mesh, b), xa), minus(point(mesh, c), xa)));
  for (int n : {a, b, c}) w[n] += area / 3.0;
}

// A bilinear quadrangle (corners cyclic): int N_k |x_xi x x_eta| by 2x2 Gauss points, exact for
// a flat parallelogram and second-order accurate for a warped one.
void addQuad(const GmshMesh& mesh, const int n[4], std::map<int, double>& w) {
  const double g = 1.0 / std::sqrt(3.0);
  const double xs[4] = {-1, 1, 1, -1}, es[4] = {-1, -1, 1, 1};
  Vec3 x[4];
  for (int k = 0; k < 4; ++k) x[k] = point(mesh, n[k]);
  for (int q = 0; q < 4; ++q) {
    const double xi = g * xs[q], eta = g * es[q];
    Vec3 dxi{0, 0, 0}, deta{0, 0, 0};
    double N[4];
    for (int k = 0; k < 4; ++k) {
      N[k] = 0.25 * (1 + xs[k] * xi) * (1 + es[k] * eta);
      for (int c = 0; c < 3; ++c) {
        dxi[c] += 0.25 * xs[k] * (1 + es[k] * eta) * x[k][c];
        deta[c] += 0.25 * es[k] * (1 + xs[k] * xi) * x[k][c];
      }
    }
    const double J = norm(cross(dxi, deta));
    for (int k = 0; k < 4; ++k) w[n[k]] += N[k] * J;
  }
}

}  // namespace

std::map<int, double> boundaryNodeWeights(const GmshMesh& mesh, const GmshBoundary& b) {
  std::map<int, double> w;
  const int npe = b.nodesPerEdge;
  for (int e = 0; e < b.numEdges(); ++e) {
    const int* n = &b.edges[static_cast<std::size_t>(e) * npe];
    switch (b.type) {
      case ElementType::Line2: {
        const double L = norm(minus(point(mesh, n[0]), point(mesh, n[1])));
        w[n[0]] += L / 2, w[n[1]] += L / 2;
        break;
      }
      case ElementType::Line3: {
        const Vec3 mid = point(mesh, n[2]);
        const double L = norm(minus(point(mesh, n[0]), mid)) + norm(minus(mid, point(mesh, n[1])));
        w[n[0]] += L / 6, w[n[1]] += L / 6, w[n[2]] += 2 * L / 3;
        break;
      }
      case ElementType::Tri3:
        addTriangle(mesh, n[0], n[1], n[2], w);
        break;
      case ElementType::Tri6:  // midside nodes 3 (0-1), 4 (1-2), 5 (2-0)
        addTriangle(mesh, n[0], n[3], n[5], w);
        addTriangle(mesh, n[3], n[1], n[4], w);
        addTriangle(mesh, n[5], n[4], n[2], w);
        addTriangle(mesh, n[3], n[4], n[5], w);
        break;
      case ElementType::Quad4:
        addQuad(mesh, n, w);
        break;
      case ElementType::Quad9: {  // midside 4 (0-1), 5 (1-2), 6 (2-3), 7 (3-0), centre 8
        const int q[4][4] = {{n[0], n[4], n[8], n[7]},
                             {n[4], n[1], n[5], n[8]},
                             {n[8], n[5], n[2], n[6]},
                             {n[7], n[8], n[6], n[3]}};
        for (const auto& sub : q) addQuad(mesh, sub, w);
        break;
      }
      default:
        throw std::invalid_argument("boundary \"" + b.name + "\" of " + mesh.source + ": no " +
                                    "nodal area rule for " + elementTypeName(b.type) + " faces");
    }
  }
  return w;
}

}  // namespace contact
