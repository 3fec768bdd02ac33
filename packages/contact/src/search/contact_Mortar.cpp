#include "contact_Mortar.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "contact_BoxTree.hpp"
#include "contact_ContactMaster.hpp"
#include "contact_MortarIntegration.hpp"
#include "contact_NodeToFace.hpp"
#include "contact_NodeToSegment.hpp"

namespace contact {

namespace {

// Parametric coordinates of a facet's nodes (Gmsh order).
std::array<double, 2> facetNode(ElementType t, int a) {
  static const double line[3] = {-1.0, 1.0, 0.0};
  static const double tri[6][2] = {{0, 0}, {1, 0}, {0, 1}, {0.5, 0}, {0.5, 0.5}, {0, 0.5}};
  static const double quad[9][2] = {{-1, -1}, {1, -1}, {1, 1},  {-1, 1}, {0, -1},
                                    {1, 0},   {0, 1},  {-1, 0}, {0, 0}};
  if (facetParametricDimension(t) == 1) return {line[a], 0.0};
  if (t == ElementType::Tri3 || t == ElementType::Tri6) return {tri[a][0], tri[a][1]};
  return {quad[a][0], quad[a][1]};
}

FacetGeometry facetOf(const MortarSurface& s, const std::vector<double>& x, int f) {
  return {s.dim, s.type, s.facets.data() + static_cast<std::size_t>(f) * s.nodesPerFacet(), &x};
}

void checkSurface(const MortarSurface& s, const std::vector<double>& x, const char* who) {
  if (s.dim != 2 && s.dim != 3)
    throw std::invalid_argument(std::string("mortar: the ") + who + " surface's dimension is " +
                                std::to_string(s.dim) + " (2 or 3)");
  if (facetParametricDimension(s.type) != s.dim - 1)
    throw std::invalid_argument(std::string("mortar: ") + elementTypeName(s.type) +
                                " is not a facet type of a " + std::to_string(s.dim) + "D mesh");
  if (s.facets.size() % s.nodesPerFacet() != 0)
    throw std::invalid_argument(std::string("mortar: the ") + who + " surface's node list is not " +
                                std::to_string(s.nodesPerFacet()) + " nodes per facet");
  const long long n = static_cast<long long>(x.size()) / s.dim;
  for (int v : s.facets)
    if (v < 0 || v >= n)
      throw std::invalid_argument(std::string("mortar: ") + who + " node " + std::to_string(v) +
                                  " outside 0.." + std::to_string(n - 1));
}

// The facet's corners in the plane's coordinates, counter-clockwise (3D), or its extent (2D:
// two points on the line, lower first).
Polygon projectedCorners(const FacetGeometry& f, const AuxiliaryPlane& plane) {
  Polygon p;
  const int corners = numCorners(f.type);
  for (int a = 0; a < corners; ++a)
    p.push_back(plane.coordinates(f.x->data() + static_cast<std::size_t>(f.dim) * f.nodes[a]));
  if (f.dim == 2) {
    if (p[0][0] > p[1][0]) std::swap(p[0], p[1]);
    p.resize(2);
  } else if (polygonArea(p) < 0.0) {
    std::reverse(p.begin(), p.end());
  }
  return p;
}

double facetSize(const FacetGeometry& f) {
  double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
  for (int a = 0; a < numCorners(f.type); ++a)
    for (int c = 0; c < f.dim; ++c) {
      const double v = (*f.x)[static_cast<std::size_t>(f.dim) * f.nodes[a] + c];
      lo[c] = std::min(lo[c], v), hi[c] = std::max(hi[c], v);
    }
  double s = 0.0;
  for (int c = 0; c < f.dim; ++c) s = std::max(s, hi[c] - lo[c]);
  return s;
}

// The quadrature points of one slave facet's covered part: weights, the multiplier-space
// functions, the slave's shape functions, and the master facet with its shape functions.
struct CoveredPoints {
  std::vector<double> w, lm, slave, master;
  std::vector<int> masterFacet;
};

// Adds the overlap of slave facet fs with master facet fm (both on the slave's plane) to `pts`.
// Returns whether it had positive measure.
bool integrateOverlap(const FacetGeometry& fs, const FacetGeometry& fm, int masterFacet,
                      const AuxiliaryPlane& plane, const Polygon& slavePoly, double size,
                      const MultiplierSpace& lm, CoveredPoints& pts) {
  const Polygon masterPoly = projectedCorners(fm, plane);
  PlaneQuadrature q;
  const double tol = 1e-10 * size;
  if (fs.dim == 2) {
    const double a = std::max(slavePoly[0][0], masterPoly[0][0]);
    const double b = std::min(slavePoly[1][0], masterPoly[1][0]);
    if (b - a <= tol) return false;
    q = intervalQuadrature(a, b);
  } else {
    const Polygon overlap = clipPolygon(masterPoly, slavePoly, tol);
    if (overlap.empty() || polygonArea(overlap) <= 1e-10 * size * size) return false;
    q = polygonQuadrature(overlap);
  }
  const int ns = fs.numNodes(), nm = fm.numNodes();
  double Ns[9], Nm[9], Nl[9];
  for (std::size_t k = 0; k < q.weights.size(); ++k) {
    double xs[2], xm[2];
    if (!plane.inverseMap(fs, q.points[k], xs) || !plane.inverseMap(fm, q.points[k], xm))
      throw std::runtime_error(
          "mortar: a quadrature point of an overlap does not map back onto its facets "
          "(a distorted facet?)");
    facetShapeFunctions(fs.type, xs, Ns, nullptr);
    facetShapeFunctions(fm.type, xm, Nm, nullptr);
    multiplierShapeFunctions(lm, xs, Nl);
    pts.w.push_back(q.weights[k]);
    pts.lm.insert(pts.lm.end(), Nl, Nl + lm.count);
    pts.slave.insert(pts.slave.end(), Ns, Ns + ns);
    pts.master.insert(pts.master.end(), Nm, Nm + nm);
    pts.masterFacet.push_back(masterFacet);
  }
  return true;
}

// What the search needs of one master facet, computed once per configuration: its nodes' box
// (grown to hold its centre, which a curved quadratic facet may have outside its nodes' box),
// its centre and its normal there.
struct MasterFacetData {
  std::vector<double> box;             // lo[0..dim-1], hi[0..dim-1] per facet
  std::vector<double> centre, normal;  // 3 values per facet
  double meanSize = 0.0, maxDiagonal = 0.0;
};

MasterFacetData masterFacetData(const MortarSurface& master, const std::vector<double>& x) {
  const int dim = master.dim, nf = master.numFacets();
  MasterFacetData m;
  m.box.reserve(static_cast<std::size_t>(2 * dim) * nf);
  m.centre.resize(3 * static_cast<std::size_t>(nf));
  m.normal.resize(3 * static_cast<std::size_t>(nf));
  for (int f = 0; f < nf; ++f) {
    const FacetGeometry fm = facetOf(master, x, f);
    const auto c = facetCentre(fm.type);
    const auto n = fm.normal(c.data());
    double* centre = &m.centre[3 * static_cast<std::size_t>(f)];
    double t[6];
    fm.evaluate(c.data(), centre, t);
    double lo[3], hi[3], diagonal = 0.0;
    for (int k = 0; k < dim; ++k) lo[k] = hi[k] = centre[k];
    for (int a = 0; a < fm.numNodes(); ++a)
      for (int k = 0; k < dim; ++k) {
        const double v = x[static_cast<std::size_t>(dim) * fm.nodes[a] + k];
        lo[k] = std::min(lo[k], v), hi[k] = std::max(hi[k], v);
      }
    for (int k = 0; k < dim; ++k) {
      m.normal[3 * static_cast<std::size_t>(f) + k] = n[k];
      diagonal += (hi[k] - lo[k]) * (hi[k] - lo[k]);
    }
    m.box.insert(m.box.end(), lo, lo + dim);
    m.box.insert(m.box.end(), hi, hi + dim);
    m.maxDiagonal = std::max(m.maxDiagonal, std::sqrt(diagonal));
    m.meanSize += facetSize(fm);
  }
  m.meanSize /= std::max(nf, 1);
  return m;
}

// The farthest a slave facet's projected corners lie from its plane's origin: every point of
// the slave polygon lies within it.
double planeReach(const FacetGeometry& fs, const AuxiliaryPlane& plane) {
  double r = 0.0;
  for (int a = 0; a < numCorners(fs.type); ++a) {
    const auto s = plane.coordinates(fs.x->data() + static_cast<std::size_t>(fs.dim) * fs.nodes[a]);
    r = std::max(r, std::hypot(s[0], s[1]));
  }
  return r;
}

// Adds one slave facet's covered points to the couplings through its dual basis.
void accumulate(const FacetGeometry& fs, const MultiplierSpace& lm, const CoveredPoints& pts,
                const MortarSurface& master, MortarCouplings& out) {
  const std::vector<double> A = dualBasisCoefficients(lm.count, pts.w, pts.lm);
  if (A.empty()) {
    ++out.singularFacets;
    return;
  }
  const int ns = fs.numNodes(), nm = master.nodesPerFacet();
  double phi[9];
  for (std::size_t q = 0; q < pts.w.size(); ++q) {
    for (int j = 0; j < lm.count; ++j) {
      phi[j] = 0.0;
      for (int b = 0; b < lm.count; ++b) phi[j] += A[j * lm.count + b] * pts.lm[q * lm.count + b];
    }
    const int* mNodes = master.facets.data() + static_cast<std::size_t>(pts.masterFacet[q]) * nm;
    for (int j = 0; j < lm.count; ++j) {
      MortarCoupling& c = out.byNode[fs.nodes[j]];
      const double wp = pts.w[q] * phi[j];
      for (int a = 0; a < ns; ++a) c.slave[fs.nodes[a]] += wp * pts.slave[q * ns + a];
      for (int k = 0; k < nm; ++k) c.master[mNodes[k]] += wp * pts.master[q * nm + k];
      c.weight += wp;
    }
  }
}

}  // namespace

MortarSurface mortarSurfaceOfBoundary(const GmshMesh& mesh, const std::string& name) {
  const GmshBoundary& g = mesh.boundary(name);
  MortarSurface s;
  s.dim = mesh.dim;
  if (mesh.dim == 3) {
    MasterFaceSurface m = masterFacesOfBoundary(mesh, g);
    s.type = m.type;
    s.facets = std::move(m.faces);
    return s;
  }
  MasterSurface m = masterSegmentsOfBoundary(mesh, g);
  s.type = g.type;
  s.facets = std::move(m.segments);
  return s;
}

MortarCouplings mortarCouplings(const std::vector<double>& x, const MortarSurface& slave,
                                const MortarSurface& master, double searchRadius) {
  checkSurface(slave, x, "slave");
  checkSurface(master, x, "master");
  if (slave.dim != master.dim)
    throw std::invalid_argument("mortar: the slave and master surfaces differ in dimension");
  if (!(searchRadius > 0.0))
    throw std::invalid_argument("mortar: the search radius must be positive");
  const int dim = slave.dim;
  MortarCouplings out;
  if (master.numFacets() == 0 || slave.numFacets() == 0) return out;
  // A master facet can overlap a slave facet only where it meets the slave polygon swept along
  // the slave plane's normal, as far as the search radius plus the master facet's own extent
  // (its centre is within the radius of the plane). That prism lies within the polygon's reach
  // of the segment origin +- L normal: the candidates are the master boxes which that segment
  // meets when grown by the reach, found in a tree of the boxes. They are the facets the slave
  // faces, not every facet within the search radius in all directions, and a graded mesh's
  // large facets do not widen the search of its small ones.
  const MasterFacetData m = masterFacetData(master, x);
  const BoxTree tree(dim, m.box);
  const MultiplierSpace lm = multiplierSpace(slave.type);
  std::vector<int> candidates;
  for (int e = 0; e < slave.numFacets(); ++e) {
    const FacetGeometry fs = facetOf(slave, x, e);
    const AuxiliaryPlane plane(fs);
    const double reach = planeReach(fs, plane);
    // A margin against rounding at the boxes' faces, far below any facet's size.
    const double margin = 1e-6 * std::max(m.meanSize, reach);
    const double L = searchRadius + m.maxDiagonal + margin;
    double a[3], b[3];
    for (int c = 0; c < dim; ++c) {
      a[c] = plane.origin[c] - L * plane.normal[c];
      b[c] = plane.origin[c] + L * plane.normal[c];
    }
    candidates.clear();
    tree.segmentQuery(a, b, reach + margin, candidates);
    const Polygon slavePoly = projectedCorners(fs, plane);
    const double size = facetSize(fs);
    CoveredPoints pts;
    for (int f : candidates) {
      const FacetGeometry fm = facetOf(master, x, f);
      bool shared = false;
      for (int p = 0; p < fm.numNodes() && !shared; ++p)
        for (int q = 0; q < fs.numNodes() && !shared; ++q) shared = fm.nodes[p] == fs.nodes[q];
      if (shared) continue;
      ++out.candidatePairs;
      // Only master facets facing the slave and within the search radius of its plane.
      const double* centre = &m.centre[3 * static_cast<std::size_t>(f)];
      const double* nm = &m.normal[3 * static_cast<std::size_t>(f)];
      double facing = 0.0;
      for (int k = 0; k < dim; ++k) facing += nm[k] * plane.normal[k];
      if (facing >= 0.0 || std::abs(plane.height(centre)) > searchRadius) continue;
      if (integrateOverlap(fs, fm, f, plane, slavePoly, size, lm, pts)) ++out.overlaps;
    }
    if (!pts.w.empty()) accumulate(fs, lm, pts, master, out);
  }
  return out;
}

std::map<int, std::array<double, 3>> slaveNodalNormals(const std::vector<double>& x,
                                                       const MortarSurface& slave) {
  checkSurface(slave, x, "slave");
  std::map<int, std::array<double, 3>> sum;
  for (int e = 0; e < slave.numFacets(); ++e) {
    const FacetGeometry f = facetOf(slave, x, e);
    for (int a = 0; a < f.numNodes(); ++a) {
      const auto xi = facetNode(f.type, a);
      const auto n = f.normal(xi.data());
      auto& s = sum[f.nodes[a]];
      for (int c = 0; c < 3; ++c) s[c] += n[c];
    }
  }
  for (auto& [node, n] : sum) {
    const double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if (!(len > 0.0))
      throw std::invalid_argument("mortar: the slave surface's normals cancel at node " +
                                  std::to_string(node) + " (a surface folded onto itself)");
    for (double& v : n) v /= len;
  }
  return sum;
}

std::map<int, double> fullMultiplierWeights(const std::vector<double>& x,
                                            const MortarSurface& slave) {
  checkSurface(slave, x, "slave");
  const MultiplierSpace lm = multiplierSpace(slave.type);
  const PlaneQuadrature q = referenceFacetQuadrature(slave.type);
  std::map<int, double> w;
  double Nl[9];
  for (int e = 0; e < slave.numFacets(); ++e) {
    const FacetGeometry f = facetOf(slave, x, e);
    for (std::size_t k = 0; k < q.weights.size(); ++k) {
      multiplierShapeFunctions(lm, q.points[k].data(), Nl);
      const double jw = q.weights[k] * f.jacobian(q.points[k].data());
      // int phi_j over the facet = int N_j (biorthogonality with the constant sum N_a = 1).
      for (int j = 0; j < lm.count; ++j) w[f.nodes[j]] += jw * Nl[j];
    }
  }
  return w;
}

}  // namespace contact
