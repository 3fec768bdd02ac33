#include "contact_MortarIntegration.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "contact_NodeToFace.hpp"

namespace contact {

int facetParametricDimension(ElementType type) {
  switch (type) {
    case ElementType::Line2:
    case ElementType::Line3:
      return 1;
    case ElementType::Tri3:
    case ElementType::Tri6:
    case ElementType::Quad4:
    case ElementType::Quad8:
    case ElementType::Quad9:
      return 2;
    default:
      throw std::invalid_argument(std::string("mortar: ") + elementTypeName(type) +
                                  " is not a contact facet type (Line2, Line3, Tri3, Tri6, Quad4, "
                                  "Quad8, Quad9)");
  }
}

std::array<double, 2> facetCentre(ElementType type) {
  if (type == ElementType::Tri3 || type == ElementType::Tri6) return {1.0 / 3.0, 1.0 / 3.0};
  return {0.0, 0.0};
}

void facetShapeFunctions(ElementType type, const double* xi, double* N, double* dN) {
  if (facetParametricDimension(type) == 2) {
    double dx[9], de[9];
    faceShapeFunctions(type, xi[0], xi[1], N, dx, de);
    if (dN)
      for (int a = 0; a < numNodes(type); ++a) dN[2 * a] = dx[a], dN[2 * a + 1] = de[a];
    return;
  }
  const double s = xi[0];
  if (type == ElementType::Line2) {
    N[0] = 0.5 * (1.0 - s), N[1] = 0.5 * (1.0 + s);
    if (dN) dN[0] = -0.5, dN[1] = 0.5;
    return;
  }
  N[0] = 0.5 * s * (s - 1.0), N[1] = 0.5 * s * (s + 1.0), N[2] = 1.0 - s * s;
  if (dN) dN[0] = s - 0.5, dN[1] = s + 0.5, dN[2] = -2.0 * s;
}

MultiplierSpace multiplierSpace(ElementType t) {
  if (t == ElementType::Tri6 || t == ElementType::Quad8) return {t, numNodes(t), 0.2};
  facetParametricDimension(t);  // throws for a non-facet
  return {t, numNodes(t)};
}

void multiplierShapeFunctions(const MultiplierSpace& space, const double* xi, double* N) {
  facetShapeFunctions(space.type, xi, N, nullptr);
  if (space.alpha == 0.0) return;
  // Tri6: midside 3 + i on the edge (i, i + 1); Quad8: midside 4 + i on the edge (i, i + 1).
  const int corners = space.type == ElementType::Tri6 ? 3 : 4;
  double mid[4];
  for (int i = 0; i < corners; ++i) mid[i] = N[corners + i];
  for (int i = 0; i < corners; ++i) {
    N[i] += space.alpha * (mid[i] + mid[(i + corners - 1) % corners]);
    N[corners + i] = (1.0 - 2.0 * space.alpha) * mid[i];
  }
}

std::vector<double> dualBasisCoefficients(int n, const std::vector<double>& w,
                                          const std::vector<double>& N) {
  std::vector<double> M(n * n, 0.0), D(n, 0.0);
  double total = 0.0;
  for (std::size_t q = 0; q < w.size(); ++q) {
    total += std::abs(w[q]);
    for (int a = 0; a < n; ++a) {
      D[a] += w[q] * N[q * n + a];
      for (int b = 0; b < n; ++b) M[a * n + b] += w[q] * N[q * n + a] * N[q * n + b];
    }
  }
  if (total <= 0.0) return {};
  // A = D M^{-1}: solve M X = I by Gauss-Jordan with partial pivoting (n <= 9), then scale rows.
  std::vector<double> inv(n * n, 0.0);
  for (int a = 0; a < n; ++a) inv[a * n + a] = 1.0;
  double scale = 0.0;
  for (int a = 0; a < n; ++a) scale = std::max(scale, std::abs(M[a * n + a]));
  for (int c = 0; c < n; ++c) {
    int p = c;
    for (int r = c + 1; r < n; ++r)
      if (std::abs(M[r * n + c]) > std::abs(M[p * n + c])) p = r;
    // A pivot at rounding level: the points do not span the functions (a sliver overlap).
    if (std::abs(M[p * n + c]) <= 1e-12 * scale) return {};
    for (int k = 0; k < n; ++k)
      std::swap(M[c * n + k], M[p * n + k]), std::swap(inv[c * n + k], inv[p * n + k]);
    const double d = 1.0 / M[c * n + c];
    for (int k = 0; k < n; ++k) M[c * n + k] *= d, inv[c * n + k] *= d;
    for (int r = 0; r < n; ++r) {
      if (r == c) continue;
      const double f = M[r * n + c];
      if (f == 0.0) continue;
      for (int k = 0; k < n; ++k)
        M[r * n + k] -= f * M[c * n + k], inv[r * n + k] -= f * inv[c * n + k];
    }
  }
  for (int a = 0; a < n; ++a)
    for (int b = 0; b < n; ++b) inv[a * n + b] *= D[a];
  return inv;
}

double polygonArea(const Polygon& p) {
  double a = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const auto& u = p[i];
    const auto& v = p[(i + 1) % p.size()];
    a += u[0] * v[1] - v[0] * u[1];
  }
  return 0.5 * a;
}

Polygon clipPolygon(const Polygon& subject, const Polygon& clip, double tolerance) {
  Polygon out = subject;
  for (std::size_t e = 0; e < clip.size() && !out.empty(); ++e) {
    const auto& a = clip[e];
    const auto& b = clip[(e + 1) % clip.size()];
    // Inside: left of a -> b (the clip polygon is counter-clockwise), with a tolerance so that a
    // subject vertex on the edge counts as inside once, not as a crossing.
    auto side = [&](const std::array<double, 2>& p) {
      return (b[0] - a[0]) * (p[1] - a[1]) - (b[1] - a[1]) * (p[0] - a[0]);
    };
    const double len = std::hypot(b[0] - a[0], b[1] - a[1]);
    Polygon in;
    in.swap(out);
    for (std::size_t i = 0; i < in.size(); ++i) {
      const auto& p = in[i];
      const auto& q = in[(i + 1) % in.size()];
      const double sp = side(p), sq = side(q);
      const bool pIn = sp >= -tolerance * len, qIn = sq >= -tolerance * len;
      if (pIn) out.push_back(p);
      if (pIn != qIn) {
        const double t = sp / (sp - sq);
        out.push_back({p[0] + t * (q[0] - p[0]), p[1] + t * (q[1] - p[1])});
      }
    }
  }
  Polygon merged;
  for (const auto& p : out)
    if (merged.empty() || std::hypot(p[0] - merged.back()[0], p[1] - merged.back()[1]) > tolerance)
      merged.push_back(p);
  while (merged.size() > 1 &&
         std::hypot(merged[0][0] - merged.back()[0], merged[0][1] - merged.back()[1]) <= tolerance)
    merged.pop_back();
  if (merged.size() < 3) merged.clear();
  return merged;
}

namespace {

const double kGauss5[5][2] = {{-0.90617984593866399280, 0.23692688505618908751},
                              {-0.53846931010568309104, 0.47862867049936646804},
                              {0.0, 0.56888888888888888889},
                              {0.53846931010568309104, 0.47862867049936646804},
                              {0.90617984593866399280, 0.23692688505618908751}};

// The 7-point degree-5 rule on a triangle: barycentric points and weights summing to 1.
struct TriPoint {
  double l0, l1, l2, w;
};
const TriPoint kTri7[7] = {
    {1.0 / 3.0, 1.0 / 3.0, 1.0 / 3.0, 0.225},
    {0.05971587178976982, 0.47014206410511509, 0.47014206410511509, 0.13239415278850618},
    {0.47014206410511509, 0.05971587178976982, 0.47014206410511509, 0.13239415278850618},
    {0.47014206410511509, 0.47014206410511509, 0.05971587178976982, 0.13239415278850618},
    {0.79742698535308720, 0.10128650732345633, 0.10128650732345633, 0.12593918054482715},
    {0.10128650732345633, 0.79742698535308720, 0.10128650732345633, 0.12593918054482715},
    {0.10128650732345633, 0.10128650732345633, 0.79742698535308720, 0.12593918054482715}};

const double kGauss4[4][2] = {{-0.86113631159405257522, 0.34785484513745385737},
                              {-0.33998104358485626480, 0.65214515486254614263},
                              {0.33998104358485626480, 0.65214515486254614263},
                              {0.86113631159405257522, 0.34785484513745385737}};

}  // namespace

PlaneQuadrature intervalQuadrature(double a, double b) {
  PlaneQuadrature r;
  const double h = 0.5 * (b - a), m = 0.5 * (a + b);
  for (const auto& g : kGauss5) {
    r.points.push_back({m + h * g[0], 0.0});
    r.weights.push_back(h * g[1]);
  }
  return r;
}

PlaneQuadrature polygonQuadrature(const Polygon& p) {
  PlaneQuadrature r;
  for (std::size_t k = 1; k + 1 < p.size(); ++k) {
    const auto &A = p[0], &B = p[k], &C = p[k + 1];
    const double area = 0.5 * ((B[0] - A[0]) * (C[1] - A[1]) - (C[0] - A[0]) * (B[1] - A[1]));
    for (const auto& t : kTri7) {
      r.points.push_back(
          {t.l0 * A[0] + t.l1 * B[0] + t.l2 * C[0], t.l0 * A[1] + t.l1 * B[1] + t.l2 * C[1]});
      r.weights.push_back(t.w * area);
    }
  }
  return r;
}

PlaneQuadrature referenceFacetQuadrature(ElementType type) {
  if (facetParametricDimension(type) == 1) return intervalQuadrature(-1.0, 1.0);
  if (type == ElementType::Tri3 || type == ElementType::Tri6)
    return polygonQuadrature({{0.0, 0.0}, {1.0, 0.0}, {0.0, 1.0}});
  PlaneQuadrature r;
  for (const auto& gx : kGauss4)
    for (const auto& gy : kGauss4) {
      r.points.push_back({gx[0], gy[0]});
      r.weights.push_back(gx[1] * gy[1]);
    }
  return r;
}

int FacetGeometry::numNodes() const {
  return contact::numNodes(type);
}

void FacetGeometry::evaluate(const double* xi, double* pos, double* tangents) const {
  const int n = numNodes(), pd = dim - 1;
  double N[9], dN[18];
  facetShapeFunctions(type, xi, N, dN);
  for (int c = 0; c < dim; ++c) {
    pos[c] = 0.0;
    for (int k = 0; k < pd; ++k) tangents[k * dim + c] = 0.0;
  }
  for (int a = 0; a < n; ++a) {
    const double* xa = x->data() + static_cast<std::size_t>(dim) * nodes[a];
    for (int c = 0; c < dim; ++c) {
      pos[c] += N[a] * xa[c];
      for (int k = 0; k < pd; ++k) tangents[k * dim + c] += dN[a * pd + k] * xa[c];
    }
  }
}

std::array<double, 3> FacetGeometry::normal(const double* xi) const {
  double p[3], t[6];
  evaluate(xi, p, t);
  std::array<double, 3> n{};
  if (dim == 2) {
    n = {t[1], -t[0], 0.0};
  } else {
    n = {t[1] * t[5] - t[2] * t[4], t[2] * t[3] - t[0] * t[5], t[0] * t[4] - t[1] * t[3]};
  }
  const double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  if (len > 0.0)
    for (double& v : n) v /= len;
  return n;
}

double FacetGeometry::jacobian(const double* xi) const {
  double p[3], t[6];
  evaluate(xi, p, t);
  if (dim == 2) return std::hypot(t[0], t[1]);
  const double n[3] = {t[1] * t[5] - t[2] * t[4], t[2] * t[3] - t[0] * t[5],
                       t[0] * t[4] - t[1] * t[3]};
  return std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
}

AuxiliaryPlane::AuxiliaryPlane(const FacetGeometry& f) : dim(f.dim) {
  const auto c = facetCentre(f.type);
  double t[6];
  f.evaluate(c.data(), origin.data(), t);
  normal = f.normal(c.data());
  double len = 0.0;
  for (int k = 0; k < dim; ++k) len += t[k] * t[k];
  len = std::sqrt(len);
  for (int k = 0; k < dim; ++k) t1[k] = t[k] / len;
  if (dim == 3) {
    // t1 x t2 = normal, so that a facet's corners in Gmsh order are counter-clockwise.
    t2 = {normal[1] * t1[2] - normal[2] * t1[1], normal[2] * t1[0] - normal[0] * t1[2],
          normal[0] * t1[1] - normal[1] * t1[0]};
  }
}

std::array<double, 2> AuxiliaryPlane::coordinates(const double* y) const {
  std::array<double, 2> s{0.0, 0.0};
  for (int c = 0; c < dim; ++c) {
    s[0] += (y[c] - origin[c]) * t1[c];
    if (dim == 3) s[1] += (y[c] - origin[c]) * t2[c];
  }
  return s;
}

double AuxiliaryPlane::height(const double* y) const {
  double h = 0.0;
  for (int c = 0; c < dim; ++c) h += (y[c] - origin[c]) * normal[c];
  return h;
}

bool AuxiliaryPlane::inverseMap(const FacetGeometry& f, const std::array<double, 2>& p,
                                double* xi) const {
  const int pd = dim - 1;
  const auto c = facetCentre(f.type);
  xi[0] = c[0], xi[1] = c[1];
  for (int it = 0; it < 30; ++it) {
    double pos[3], t[6];
    f.evaluate(xi, pos, t);
    const auto s = coordinates(pos);
    const double r0 = s[0] - p[0], r1 = pd == 2 ? s[1] - p[1] : 0.0;
    // J[i][k] = d s_i / d xi_k
    double J[2][2] = {{0.0, 0.0}, {0.0, 0.0}};
    for (int k = 0; k < pd; ++k)
      for (int cc = 0; cc < dim; ++cc) {
        J[0][k] += t[k * dim + cc] * t1[cc];
        if (pd == 2) J[1][k] += t[k * dim + cc] * t2[cc];
      }
    if (r0 == 0.0 && r1 == 0.0) return true;
    double d0 = 0.0, d1 = 0.0;
    if (pd == 1) {
      if (J[0][0] == 0.0) return false;
      d0 = r0 / J[0][0];
    } else {
      const double det = J[0][0] * J[1][1] - J[0][1] * J[1][0];
      if (det == 0.0) return false;
      d0 = (J[1][1] * r0 - J[0][1] * r1) / det;
      d1 = (-J[1][0] * r0 + J[0][0] * r1) / det;
    }
    xi[0] -= d0, xi[1] -= d1;
    // Parametric coordinates are O(1): a step at rounding level is convergence, whatever the
    // coordinates' magnitude.
    if (std::abs(d0) + std::abs(d1) <= 1e-13) return true;
  }
  return false;
}

}  // namespace contact
