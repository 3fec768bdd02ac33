#include "contact_NodeToFace.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <memory>
#include <set>
#include <stdexcept>
#include <string>

#include "contact_BucketGrid.hpp"

namespace contact {

namespace {

using Vec = std::array<double, 3>;

Vec operator+(const Vec& a, const Vec& b) {
  return {a[0] + b[0], a[1] + b[1], a[2] + b[2]};
}
Vec operator-(const Vec& a, const Vec& b) {
  return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}
Vec operator*(double s, const Vec& a) {
  return {s * a[0], s * a[1], s * a[2]};
}
double dot(const Vec& a, const Vec& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
Vec cross(const Vec& a, const Vec& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
double norm(const Vec& a) {
  return std::sqrt(dot(a, a));
}
Vec unit(const Vec& a) {
  return (1.0 / norm(a)) * a;
}

bool isTriangle(ElementType t) {
  return plasticity::elementInfo(t).simplex;
}

// Reference corners of the face types, in Gmsh's order.
const double kTriCorners[3][2] = {{0, 0}, {1, 0}, {0, 1}};
const double kQuadCorners[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};

std::array<double, 2> cornerParam(ElementType t, int c) {
  const double* p = isTriangle(t) ? kTriCorners[c] : kQuadCorners[c];
  return {p[0], p[1]};
}

// The point of local edge j (corner j to corner j+1) at s in [-1, 1] (s = -1 at corner j).
std::array<double, 2> edgeParam(ElementType t, int j, double s) {
  const int nc = numCorners(t);
  const auto a = cornerParam(t, j), b = cornerParam(t, (j + 1) % nc);
  const double w = 0.5 * (s + 1.0);
  return {a[0] + w * (b[0] - a[0]), a[1] + w * (b[1] - a[1])};
}

// 1D quadratic Lagrange polynomials on the nodes -1, 0, 1 and their derivatives.
void lagrange1d(double s, double l[3], double dl[3]) {
  l[0] = 0.5 * s * (s - 1.0), l[1] = 1.0 - s * s, l[2] = 0.5 * s * (s + 1.0);
  dl[0] = s - 0.5, dl[1] = -2.0 * s, dl[2] = s + 0.5;
}

// The face's geometry on the current configuration: its node positions.
struct Face {
  ElementType type;
  int nodes = 0;
  std::array<Vec, 9> x{};
  double size = 0.0;  // largest corner-to-corner distance

  void eval(double xi, double eta, Vec* p, Vec* dxi, Vec* deta) const {
    double n[9], a[9], b[9];
    faceShapeFunctions(type, xi, eta, n, a, b);
    Vec P{0, 0, 0}, A{0, 0, 0}, B{0, 0, 0};
    for (int k = 0; k < nodes; ++k) {
      P = P + n[k] * x[k];
      A = A + a[k] * x[k];
      B = B + b[k] * x[k];
    }
    if (p) *p = P;
    if (dxi) *dxi = A;
    if (deta) *deta = B;
  }
  Vec normal(double xi, double eta) const {
    Vec a, b;
    eval(xi, eta, nullptr, &a, &b);
    return unit(cross(a, b));
  }
};

struct FaceProjection {
  std::array<double, 2> xi{};
  Vec point{};
  double dist2 = std::numeric_limits<double>::infinity();
  int edge = -1;    // local edge the point is on (boundary minimum), or -1 (interior)
  int corner = -1;  // local corner the point is at, or -1
};

// Projects (xi, eta) onto the reference face; returns true when a bound was active.
bool clampToFace(ElementType t, std::array<double, 2>& p) {
  const std::array<double, 2> q = p;
  if (isTriangle(t)) {
    p[0] = std::max(p[0], 0.0);
    p[1] = std::max(p[1], 0.0);
    if (p[0] + p[1] > 1.0) {
      p[0] = std::clamp(0.5 * (p[0] - p[1] + 1.0), 0.0, 1.0);
      p[1] = 1.0 - p[0];
    }
  } else {
    p[0] = std::clamp(p[0], -1.0, 1.0);
    p[1] = std::clamp(p[1], -1.0, 1.0);
  }
  return p != q;
}

bool onFaceBoundary(ElementType t, const std::array<double, 2>& p) {
  const double tol = 1e-13;
  if (isTriangle(t)) return p[0] <= tol || p[1] <= tol || p[0] + p[1] >= 1.0 - tol;
  return std::abs(p[0]) >= 1.0 - tol || std::abs(p[1]) >= 1.0 - tol;
}

// Newton for min |x(xi, eta) - xs|^2 / 2, projected onto the reference face. The geometry is
// (bi)quadratic, so central differences of the tangents give its second derivatives exactly.
std::array<double, 2> newtonOnFace(const Face& f, const Vec& xs, int maxIterations) {
  std::array<double, 2> p = isTriangle(f.type) ? std::array<double, 2>{1.0 / 3.0, 1.0 / 3.0}
                                               : std::array<double, 2>{0.0, 0.0};
  const double h = 1e-3;
  for (int it = 0; it < maxIterations; ++it) {
    Vec x, a, b;
    f.eval(p[0], p[1], &x, &a, &b);
    const Vec d = x - xs;
    const double g0 = dot(d, a), g1 = dot(d, b);
    double H00 = dot(a, a), H01 = dot(a, b), H11 = dot(b, b);
    if (f.nodes > numCorners(f.type)) {
      Vec ap, am, bp, bm, bq, bqm;
      f.eval(p[0] + h, p[1], nullptr, &ap, &bp);
      f.eval(p[0] - h, p[1], nullptr, &am, &bm);
      f.eval(p[0], p[1] + h, nullptr, nullptr, &bq);
      f.eval(p[0], p[1] - h, nullptr, nullptr, &bqm);
      const Vec xaa = (0.5 / h) * (ap - am), xab = (0.5 / h) * (bp - bm),
                xbb = (0.5 / h) * (bq - bqm);
      const double E00 = H00 + dot(d, xaa), E01 = H01 + dot(d, xab), E11 = H11 + dot(d, xbb);
      // Far on the concave side the exact Hessian may be indefinite and Newton would run away;
      // the Gauss-Newton part alone is always a descent direction.
      if (E00 > 0.1 * H00 && E11 > 0.1 * H11 &&
          E00 * E11 - E01 * E01 > 0.01 * (H00 * H11 - H01 * H01))
        H00 = E00, H01 = E01, H11 = E11;
    }
    const double det = H00 * H11 - H01 * H01;
    std::array<double, 2> next{p[0] - (H11 * g0 - H01 * g1) / det,
                               p[1] - (H00 * g1 - H01 * g0) / det};
    clampToFace(f.type, next);
    const bool done = std::abs(next[0] - p[0]) + std::abs(next[1] - p[1]) <= 1e-15;
    p = next;
    if (done) break;
  }
  return p;
}

// 1D Newton along local edge j (a curve of the face), clamped to its ends, compared with them.
FaceProjection projectOnEdge(const Face& f, int j, const Vec& xs, int maxIterations) {
  const auto a = edgeParam(f.type, j, -1.0), b = edgeParam(f.type, j, 1.0);
  const double da[2] = {0.5 * (b[0] - a[0]), 0.5 * (b[1] - a[1])};  // d(xi, eta)/ds
  auto tangent = [&](double s, Vec& x) {
    const auto p = edgeParam(f.type, j, s);
    Vec tx, ty;
    f.eval(p[0], p[1], &x, &tx, &ty);
    return da[0] * tx + da[1] * ty;
  };
  double s = 0.0;
  const double h = 1e-3;
  for (int it = 0; it < maxIterations; ++it) {
    Vec x, xp, xm;
    const Vec t = tangent(s, x);
    const Vec tt = (0.5 / h) * (tangent(s + h, xp) - tangent(s - h, xm));
    const Vec d = x - xs;
    const double g = dot(d, t), gn = dot(t, t);
    double H = gn + dot(d, tt);
    if (H < 0.1 * gn) H = gn;
    const double next = std::clamp(s - g / H, -1.0, 1.0);
    const bool done = std::abs(next - s) <= 1e-15;
    s = next;
    if (done) break;
  }
  FaceProjection best;
  for (double cand : {s, -1.0, 1.0}) {
    const auto p = edgeParam(f.type, j, cand);
    Vec x;
    f.eval(p[0], p[1], &x, nullptr, nullptr);
    const double d2 = dot(x - xs, x - xs);
    if (d2 < best.dist2) {
      best.xi = p;
      best.point = x;
      best.dist2 = d2;
      best.edge = j;
      const int nc = numCorners(f.type);
      best.corner = cand == -1.0 ? j : cand == 1.0 ? (j + 1) % nc : -1;
    }
  }
  return best;
}

FaceProjection projectOnFace(const Face& f, const Vec& xs, int maxIterations) {
  FaceProjection p;
  p.xi = newtonOnFace(f, xs, maxIterations);
  f.eval(p.xi[0], p.xi[1], &p.point, nullptr, nullptr);
  p.dist2 = dot(p.point - xs, p.point - xs);
  bool searchEdges = onFaceBoundary(f.type, p.xi);
  // A curved face may have another local minimum: a closer corner sends the search to the edges.
  const int nc = numCorners(f.type);
  for (int c = 0; c < nc && !searchEdges; ++c)
    searchEdges = dot(f.x[c] - xs, f.x[c] - xs) < p.dist2;
  if (!searchEdges) return p;
  FaceProjection best = onFaceBoundary(f.type, p.xi) ? FaceProjection{} : p;
  for (int j = 0; j < nc; ++j) {
    const FaceProjection e = projectOnEdge(f, j, xs, maxIterations);
    if (e.dist2 < best.dist2) best = e;
  }
  return best;
}

// Outward direction in the face's tangent plane across local edge j at the point p.
Vec outwardAcrossEdge(const Face& f, int j, const std::array<double, 2>& p) {
  const auto a = edgeParam(f.type, j, -1.0), b = edgeParam(f.type, j, 1.0);
  Vec tx, ty;
  f.eval(p[0], p[1], nullptr, &tx, &ty);
  const Vec t = (b[0] - a[0]) * tx + (b[1] - a[1]) * ty;  // along the edge, corner j to j+1
  return unit(cross(t, cross(tx, ty)));
}

using EdgeKey = std::uint64_t;
EdgeKey edgeKey(int a, int b) {
  if (a > b) std::swap(a, b);
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) |
         static_cast<std::uint32_t>(b);
}

void checkFaces(const MasterFaceSurface& m, int numNodes, const char* who) {
  if (elementDimension(m.type) != 2)
    throw std::invalid_argument(std::string(who) + ": master face type " + elementTypeName(m.type) +
                                " is not a surface element");
  if (m.faces.size() % m.nodesPerFace() != 0)
    throw std::invalid_argument(std::string(who) + ": the face list's size " +
                                std::to_string(m.faces.size()) + " is not a multiple of " +
                                std::to_string(m.nodesPerFace()));
  for (std::size_t i = 0; i < m.faces.size(); ++i)
    if (m.faces[i] < 0 || m.faces[i] >= numNodes)
      throw std::invalid_argument(
          std::string(who) + ": face " + std::to_string(i / m.nodesPerFace()) + " has node " +
          std::to_string(m.faces[i]) + " outside 0.." + std::to_string(numNodes - 1));
}

std::string nodeList(const std::vector<int>& nodes) {
  std::string s;
  for (std::size_t i = 0; i < nodes.size() && i < 10; ++i)
    s += (i ? ", " : "") + std::to_string(nodes[i]);
  if (nodes.size() > 10) s += ", ... (" + std::to_string(nodes.size()) + " nodes)";
  return s;
}

}  // namespace

void faceShapeFunctions(ElementType type, double xi, double eta, double* n, double* dNdXi,
                        double* dNdEta) {
  double a[9], b[9];
  double* dx = dNdXi ? dNdXi : a;
  double* de = dNdEta ? dNdEta : b;
  switch (type) {
    case ElementType::Tri3:
      n[0] = 1.0 - xi - eta, n[1] = xi, n[2] = eta;
      dx[0] = -1, dx[1] = 1, dx[2] = 0;
      de[0] = -1, de[1] = 0, de[2] = 1;
      return;
    case ElementType::Tri6: {
      const double L[3] = {1.0 - xi - eta, xi, eta}, Lx[3] = {-1, 1, 0}, Le[3] = {-1, 0, 1};
      for (int i = 0; i < 3; ++i) {
        n[i] = L[i] * (2.0 * L[i] - 1.0);
        dx[i] = (4.0 * L[i] - 1.0) * Lx[i];
        de[i] = (4.0 * L[i] - 1.0) * Le[i];
        const int j = (i + 1) % 3;  // midside node 3 + i on the edge (i, i+1)
        n[3 + i] = 4.0 * L[i] * L[j];
        dx[3 + i] = 4.0 * (Lx[i] * L[j] + L[i] * Lx[j]);
        de[3 + i] = 4.0 * (Le[i] * L[j] + L[i] * Le[j]);
      }
      return;
    }
    case ElementType::Quad4:
      for (int i = 0; i < 4; ++i) {
        const double xa = kQuadCorners[i][0], ea = kQuadCorners[i][1];
        n[i] = 0.25 * (1 + xa * xi) * (1 + ea * eta);
        dx[i] = 0.25 * xa * (1 + ea * eta);
        de[i] = 0.25 * ea * (1 + xa * xi);
      }
      return;
    case ElementType::Quad8: {
      for (int i = 0; i < 4; ++i) {
        const double xa = kQuadCorners[i][0], ea = kQuadCorners[i][1];
        const double A = 1 + xa * xi, B = 1 + ea * eta;
        n[i] = 0.25 * A * B * (xa * xi + ea * eta - 1.0);
        dx[i] = 0.25 * xa * B * (2.0 * xa * xi + ea * eta);
        de[i] = 0.25 * ea * A * (xa * xi + 2.0 * ea * eta);
      }
      // Midside nodes 4..7 at (0,-1), (1,0), (0,1), (-1,0).
      const double ms[4][2] = {{0, -1}, {1, 0}, {0, 1}, {-1, 0}};
      for (int k = 0; k < 4; ++k) {
        const double xa = ms[k][0], ea = ms[k][1];
        if (xa == 0.0) {
          n[4 + k] = 0.5 * (1 - xi * xi) * (1 + ea * eta);
          dx[4 + k] = -xi * (1 + ea * eta);
          de[4 + k] = 0.5 * (1 - xi * xi) * ea;
        } else {
          n[4 + k] = 0.5 * (1 + xa * xi) * (1 - eta * eta);
          dx[4 + k] = 0.5 * xa * (1 - eta * eta);
          de[4 + k] = -eta * (1 + xa * xi);
        }
      }
      return;
    }
    case ElementType::Quad9: {
      double lx[3], dlx[3], le[3], dle[3];
      lagrange1d(xi, lx, dlx);
      lagrange1d(eta, le, dle);
      // Node k at (I[k], J[k]) of the 1D nodes -1, 0, 1 (indices 0, 1, 2).
      const int I[9] = {0, 2, 2, 0, 1, 2, 1, 0, 1}, J[9] = {0, 0, 2, 2, 0, 1, 2, 1, 1};
      for (int k = 0; k < 9; ++k) {
        n[k] = lx[I[k]] * le[J[k]];
        dx[k] = dlx[I[k]] * le[J[k]];
        de[k] = lx[I[k]] * dle[J[k]];
      }
      return;
    }
    default:
      throw std::invalid_argument(std::string("faceShapeFunctions: ") + elementTypeName(type) +
                                  " is not a face type");
  }
}

std::vector<int> findFaceOrientationErrors(const MasterFaceSurface& master) {
  checkFaces(master, std::numeric_limits<int>::max(), "findFaceOrientationErrors");
  const int npf = master.nodesPerFace(), nc = numCorners(master.type);
  std::map<std::pair<int, int>, int> directed;
  std::map<EdgeKey, int> shared;
  for (int f = 0; f < master.numFaces(); ++f) {
    const int* v = &master.faces[static_cast<std::size_t>(f) * npf];
    for (int j = 0; j < nc; ++j) {
      ++directed[{v[j], v[(j + 1) % nc]}];
      ++shared[edgeKey(v[j], v[(j + 1) % nc])];
    }
  }
  std::set<int> bad;
  for (const auto& [e, count] : directed)
    if (count > 1 || shared[edgeKey(e.first, e.second)] > 2) bad.insert({e.first, e.second});
  return std::vector<int>(bad.begin(), bad.end());
}

ContactRowsResult computeNodeToFace(const std::vector<double>& coords,
                                    const std::vector<int>& slaveNodes,
                                    const MasterFaceSurface& master,
                                    const ContactSearchOptions& options,
                                    const std::vector<double>& displacement) {
  const char* who = "computeNodeToFace";
  if (coords.size() % 3 != 0)
    throw std::invalid_argument("computeNodeToFace: coords must hold x, y, z per node");
  const int numNodes = static_cast<int>(coords.size() / 3);
  if (!displacement.empty() && displacement.size() != coords.size())
    throw std::invalid_argument(
        "computeNodeToFace: the displacement must be empty or hold x, y, z per node (" +
        std::to_string(coords.size()) + " values), not " + std::to_string(displacement.size()));
  validateSearchOptions(options, who);
  checkFaces(master, numNodes, who);
  for (int s : slaveNodes)
    if (s < 0 || s >= numNodes)
      throw std::invalid_argument("computeNodeToFace: slave node " + std::to_string(s) +
                                  " outside 0.." + std::to_string(numNodes - 1));
  const std::vector<int> bad = findFaceOrientationErrors(master);
  if (!bad.empty())
    throw std::invalid_argument(
        "computeNodeToFace: the master surface is inconsistently oriented or non-manifold "
        "(an edge traversed twice in one direction or shared by more than two faces) at "
        "node(s) " +
        nodeList(bad) + "; take the faces from the body's elements (masterFacesOfBoundary)");

  const int npf = master.nodesPerFace(), nc = numCorners(master.type), nf = master.numFaces();
  auto position = [&](int n) -> Vec {
    Vec x{coords[3 * n], coords[3 * n + 1], coords[3 * n + 2]};
    if (!displacement.empty())
      x = x + Vec{displacement[3 * n], displacement[3 * n + 1], displacement[3 * n + 2]};
    return x;
  };
  auto faceNode = [&](int f, int k) { return master.faces[static_cast<std::size_t>(f) * npf + k]; };

  std::vector<Face> faces(nf);
  std::vector<double> boxes(6 * static_cast<std::size_t>(nf));
  std::map<EdgeKey, std::vector<std::pair<int, int>>> edgeFaces;  // (face, local edge)
  std::map<int, std::vector<std::pair<int, int>>> vertexFaces;    // (face, local corner)
  double extentSum = 0.0;
  const double r = options.searchRadius;
  for (int f = 0; f < nf; ++f) {
    Face& F = faces[f];
    F.type = master.type;
    F.nodes = npf;
    for (int k = 0; k < npf; ++k) F.x[k] = position(faceNode(f, k));
    for (int a = 0; a < nc; ++a)
      for (int b = a + 1; b < nc; ++b) F.size = std::max(F.size, norm(F.x[a] - F.x[b]));
    Vec ta, tb;
    F.eval(isTriangle(F.type) ? 1.0 / 3.0 : 0.0, isTriangle(F.type) ? 1.0 / 3.0 : 0.0, nullptr, &ta,
           &tb);
    if (!(norm(cross(ta, tb)) > 1e-12 * F.size * F.size))
      throw std::invalid_argument("computeNodeToFace: face " + std::to_string(f) +
                                  " is degenerate (zero area)");
    // Bezier control points: the curved face lies in their convex hull.
    std::vector<Vec> control(F.x.begin(), F.x.begin() + nc);
    if (npf > nc) {
      for (int j = 0; j < nc; ++j)
        control.push_back(2.0 * F.x[nc + j] - 0.5 * (F.x[j] + F.x[(j + 1) % nc]));
      if (!isTriangle(F.type)) {
        // Quad8's centre value is that of its serendipity interpolant.
        const Vec c = npf == 9 ? F.x[8]
                               : 0.5 * (F.x[4] + F.x[5] + F.x[6] + F.x[7]) -
                                     0.25 * (F.x[0] + F.x[1] + F.x[2] + F.x[3]);
        auto q = [](const Vec& l, const Vec& m, const Vec& rr) { return 2.0 * m - 0.5 * (l + rr); };
        control.push_back(2.0 * q(F.x[7], c, F.x[5]) -
                          0.5 * (q(F.x[0], F.x[4], F.x[1]) + q(F.x[3], F.x[6], F.x[2])));
      }
    }
    double* box = &boxes[6 * static_cast<std::size_t>(f)];
    for (int i = 0; i < 3; ++i) {
      box[i] = std::numeric_limits<double>::infinity();
      box[3 + i] = -box[i];
      for (const Vec& p : control) {
        box[i] = std::min(box[i], p[i]);
        box[3 + i] = std::max(box[3 + i], p[i]);
      }
    }
    double ext = 0.0;
    for (int i = 0; i < 3; ++i) {
      ext = std::max(ext, box[3 + i] - box[i]);
      box[i] -= r;
      box[3 + i] += r;
    }
    extentSum += ext;
    for (int j = 0; j < nc; ++j) {
      edgeFaces[edgeKey(faceNode(f, j), faceNode(f, (j + 1) % nc))].push_back({f, j});
      vertexFaces[faceNode(f, j)].push_back({f, j});
    }
  }

  ContactRowsResult result;
  result.allPairs = static_cast<long long>(slaveNodes.size()) * nf;
  std::unique_ptr<BucketGrid> grid;
  std::vector<int> everyFace;
  if (options.bruteForce) {
    everyFace.resize(nf);
    for (int f = 0; f < nf; ++f) everyFace[f] = f;
  } else if (nf > 0) {
    const double h = options.cellSize > 0.0 ? options.cellSize : std::max(extentSum / nf, r);
    grid = std::make_unique<BucketGrid>(3, boxes, h);
    result.gridCells = grid->occupiedCells();
    result.cellSize = grid->cellSize();
  }

  auto neighbourAcross = [&](int f, int j) {
    const auto& list = edgeFaces.at(edgeKey(faceNode(f, j), faceNode(f, (j + 1) % nc)));
    for (const auto& [g, k] : list)
      if (g != f) return std::make_pair(g, k);
    return std::make_pair(-1, -1);
  };

  double shape[9];
  for (int slave : slaveNodes) {
    const Vec xs = position(slave);
    const std::vector<int>* cand = options.bruteForce ? &everyFace : nullptr;
    if (grid) cand = grid->candidates(xs.data());
    int best = -1;
    FaceProjection bp;
    if (cand)
      for (int f : *cand) {
        bool own = false;
        for (int k = 0; k < npf; ++k) own = own || faceNode(f, k) == slave;
        if (own) continue;
        ++result.candidatePairs;
        const FaceProjection p = projectOnFace(faces[f], xs, options.maxNewtonIterations);
        // On a near tie (a node on the normal through an edge) an interior projection wins, so
        // the normal changes continuously as the node leaves the edge's wedge.
        const double tie = 1e-12 * bp.dist2;
        if (best < 0 || p.dist2 < bp.dist2 - tie ||
            (p.dist2 <= bp.dist2 + tie && bp.edge >= 0 && p.edge < 0)) {
          best = f;
          bp = p;
        }
      }
    if (best < 0 || std::sqrt(bp.dist2) > r) {
      ++result.beyondRadius;
      continue;
    }
    const Face& F = faces[best];
    const Vec d = xs - bp.point;
    Vec n = F.normal(bp.xi[0], bp.xi[1]);
    ProjectionKind kind = ProjectionKind::Interior;
    if (bp.edge >= 0) {
      // The face's edges through the point: one, or the two meeting at the corner.
      std::vector<int> edges{bp.edge};
      if (bp.corner >= 0) edges = {bp.corner, (bp.corner + nc - 1) % nc};
      bool beyondFree = false, allShared = true;
      for (int j : edges) {
        if (neighbourAcross(best, j).first >= 0) continue;
        allShared = false;
        const double beyond = dot(d, outwardAcrossEdge(F, j, bp.xi));
        beyondFree = beyondFree || beyond > options.endTolerance * F.size;
      }
      if (beyondFree) {
        if (options.endPolicy == EndPolicy::Drop) {
          ++result.beyondEnd;
          continue;
        }
        kind = ProjectionKind::End;
      } else if (allShared || bp.corner >= 0) {
        // The normalized sum of the normals of the faces sharing the point.
        Vec sum{0, 0, 0};
        if (bp.corner >= 0) {
          for (const auto& [g, c] : vertexFaces.at(faceNode(best, bp.corner))) {
            const auto q = cornerParam(master.type, c);
            sum = sum + faces[g].normal(q[0], q[1]);
          }
        } else {
          const auto [g, k] = neighbourAcross(best, bp.edge);
          // s along this face's edge; the neighbour traverses the edge the other way if its
          // corner k is not this edge's first node.
          const auto a = edgeParam(F.type, bp.edge, -1.0), b = edgeParam(F.type, bp.edge, 1.0);
          const double w = std::abs(b[0] - a[0]) > std::abs(b[1] - a[1])
                               ? (bp.xi[0] - a[0]) / (b[0] - a[0])
                               : (bp.xi[1] - a[1]) / (b[1] - a[1]);
          const double s = 2.0 * w - 1.0;
          const bool same = faceNode(g, k) == faceNode(best, bp.edge);
          const auto q = edgeParam(master.type, k, same ? s : -s);
          sum = n + faces[g].normal(q[0], q[1]);
        }
        const Vec avg = norm(sum) > 1e-12 ? unit(sum) : n;
        // d / |d| outside the corner's cone, unless d may be noise (kCornerSnap).
        const double dist = norm(d);
        n = (dist > kCornerSnap * F.size && dot(d, avg) > 0.0) ? (1.0 / dist) * d : avg;
        kind = bp.corner >= 0 ? ProjectionKind::Corner : ProjectionKind::Edge;
      }
    }
    ContactRow row;
    row.slaveNode = slave;
    row.facet = best;
    row.xi = bp.xi;
    row.kind = kind;
    row.point = bp.point;
    row.normal = n;
    row.gap = dot(d, n);
    faceShapeFunctions(master.type, bp.xi[0], bp.xi[1], shape, nullptr, nullptr);
    row.entries.reserve(3 + 3 * npf);
    for (int c = 0; c < 3; ++c) row.entries.push_back({slave, c, -n[c]});
    for (int k = 0; k < npf; ++k)
      for (int c = 0; c < 3; ++c) row.entries.push_back({faceNode(best, k), c, shape[k] * n[c]});
    result.rows.push_back(std::move(row));
  }
  return result;
}

MasterFaceSurface masterFacesOfBoundary(const GmshMesh& mesh, const GmshBoundary& boundary) {
  if (mesh.dim != 3)
    throw std::invalid_argument(mesh.source + ": boundary \"" + boundary.name +
                                "\": master faces need a 3D mesh");
  MasterFaceSurface m;
  for (int i = 0; i < boundary.numEdges(); ++i) {
    if (boundary.edgeBody[i] < 0)
      throw std::invalid_argument(mesh.source + ": face " + std::to_string(i) + " of boundary \"" +
                                  boundary.name + "\" is on no body");
    const GmshBody& b = mesh.bodies[boundary.edgeBody[i]];
    const ElementType t = facetType(b.type);
    if (i == 0) m.type = t;
    if (t != m.type)
      throw std::invalid_argument(mesh.source + ": boundary \"" + boundary.name +
                                  "\" has faces of different types (" + elementTypeName(m.type) +
                                  ", " + elementTypeName(t) + ")");
    const int* el =
        &b.connectivity[static_cast<std::size_t>(boundary.edgeElement[i]) * b.nodesPerElement()];
    for (int k : elementFacetNodes(b.type, boundary.edgeLocalEdge[i])) m.faces.push_back(el[k]);
  }
  return m;
}

}  // namespace contact
