#include "contact_RecoveredFields.hpp"

#include <Teuchos_CommHelpers.hpp>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include "contact_TangentialRows.hpp"

namespace contact {

namespace {

// The monomials of the tangential coordinates (xi, eta) up to `degree` (1 or 2) in nt = 1 or 2
// variables, the constant first: 1, xi [, eta] [, xi^2 [, xi eta, eta^2]].
int monomials(int nt, int degree, const double* xi, double* out) {
  int k = 0;
  out[k++] = 1.0;
  for (int a = 0; a < nt; ++a) out[k++] = xi[a];
  if (degree == 2)
    for (int a = 0; a < nt; ++a)
      for (int b = a; b < nt; ++b) out[k++] = xi[a] * xi[b];
  return k;
}

// The constant coefficient of the least-squares polynomial through (xi_k, v_k) (coordinates
// scaled to about 1) by modified Gram-Schmidt; false when the patch leaves a coefficient
// undetermined (a column dependent on the others to 1e-8).
bool constantOfFit(const std::vector<std::array<double, 2>>& xi, const std::vector<double>& v,
                   int nt, int degree, double& c0) {
  const std::size_t m = xi.size();
  double row[6];
  const int k = monomials(nt, degree, xi[0].data(), row);
  if (static_cast<int>(m) < k) return false;
  std::vector<std::vector<double>> q(k, std::vector<double>(m));
  for (std::size_t r = 0; r < m; ++r) {
    monomials(nt, degree, xi[r].data(), row);
    for (int c = 0; c < k; ++c) q[c][r] = row[c];
  }
  std::vector<std::vector<double>> R(k, std::vector<double>(k, 0.0));
  for (int c = 0; c < k; ++c) {
    double before = 0.0;
    for (double e : q[c]) before += e * e;
    for (int b = 0; b < c; ++b) {
      double d = 0.0;
      for (std::size_t r = 0; r < m; ++r) d += q[b][r] * q[c][r];
      R[b][c] = d;
      for (std::size_t r = 0; r < m; ++r) q[c][r] -= d * q[b][r];
    }
    double after = 0.0;
    for (double e : q[c]) after += e * e;
    if (after <= 1e-16 * before) return false;
    R[c][c] = std::sqrt(after);
    for (double& e : q[c]) e /= R[c][c];
  }
  std::vector<double> y(k, 0.0);
  for (int c = 0; c < k; ++c)
    for (std::size_t r = 0; r < m; ++r) y[c] += q[c][r] * v[r];
  for (int c = k - 1; c >= 0; --c) {
    for (int b = c + 1; b < k; ++b) y[c] -= R[c][b] * y[b];
    y[c] /= R[c][c];
  }
  c0 = y[0];
  return true;
}

}  // namespace

std::vector<double> patchRecovery(const std::vector<std::array<double, 3>>& x,
                                  const std::vector<std::array<double, 3>>& normal,
                                  const std::vector<double>& value,
                                  const std::vector<std::vector<int>>& patch, int dim,
                                  const std::vector<int>& degree) {
  std::vector<double> out(value);
  const int nt = dim - 1;  // tangential coordinates
  for (std::size_t i = 0; i < x.size(); ++i) {
    const std::vector<int>& p = patch[i];
    if (p.empty()) continue;
    const std::vector<std::array<double, 3>> t = tangentBasis(normal[i], dim);
    // Coordinates from the node, so that the fit's value there is its constant coefficient.
    std::vector<std::array<double, 2>> xi(p.size(), std::array<double, 2>{0.0, 0.0});
    std::vector<double> v(p.size());
    double scale = 0.0;
    for (std::size_t k = 0; k < p.size(); ++k) {
      for (int a = 0; a < nt; ++a) {
        for (int c = 0; c < dim; ++c) xi[k][a] += (x[p[k]][c] - x[i][c]) * t[a][c];
        scale = std::max(scale, std::abs(xi[k][a]));
      }
      v[k] = value[p[k]];
    }
    if (scale == 0.0) continue;
    for (auto& e : xi)
      for (int a = 0; a < nt; ++a) e[a] /= scale;
    // A patch too small or too flat for the degree tries the lower one, then keeps the value.
    for (int d = degree[i]; d >= 1; --d) {
      double c0 = 0.0;
      if (constantOfFit(xi, v, nt, d, c0)) {
        out[i] = c0;
        break;
      }
    }
  }
  return out;
}

std::vector<std::array<double, 3>> mirrorImages(const std::array<double, 3>& onPlanes,
                                                const std::vector<int>& components,
                                                const std::array<double, 3>& point, double tol) {
  std::vector<std::array<double, 3>> orbit{point};
  for (int c : components) {
    // Reflecting across another plane keeps this coordinate: the point's own decides.
    if (std::abs(point[c] - onPlanes[c]) <= tol) continue;
    const std::size_t m = orbit.size();
    for (std::size_t k = 0; k < m; ++k) {
      std::array<double, 3> image = orbit[k];
      image[c] = 2.0 * onPlanes[c] - image[c];
      orbit.push_back(image);
    }
  }
  orbit.erase(orbit.begin());
  return orbit;
}

namespace {

// The points of the pressure recovery: the contact nodes first, then the mirror images.
struct RecoveryPoints {
  std::vector<std::array<double, 3>> x, normal;
  std::vector<double> value;
  std::vector<std::vector<int>> patch;
  std::vector<int> degree;
};

// Per node: itself and the nodes sharing a facet of its pair's slave boundary with it that have
// a row in the same pair. The degree of each node's fit is its slave facets': on quadratic
// facets a linear fit over the ring would flatten a curved pressure (Tet10 at a/3.8: -2.1 % at
// the peak), where their nodal values are smooth already.
RecoveryPoints facetPatches(const std::vector<ContactNode>& nodes, const std::vector<int>& pairOf,
                            const ElasticContactProblem& problem) {
  std::map<std::pair<int, int>, int> index;  // (pair, slave node) -> node
  for (std::size_t i = 0; i < nodes.size(); ++i)
    index[{pairOf[i], nodes[i].slaveNode}] = static_cast<int>(i);
  std::vector<std::set<int>> near(nodes.size());
  std::vector<int> pairDegree(problem.pairs.size(), 1);
  for (std::size_t k = 0; k < problem.pairs.size(); ++k) {
    const GmshBoundary& b = problem.mesh.boundary(problem.pairs[k].spec.slave);
    pairDegree[k] = numNodes(b.type) > numCorners(b.type) ? 2 : 1;
    for (int e = 0; e < b.numEdges(); ++e) {
      std::vector<int> onFacet;
      for (int a = 0; a < b.nodesPerEdge; ++a) {
        const auto it = index.find({static_cast<int>(k), b.edges[e * b.nodesPerEdge + a]});
        if (it != index.end()) onFacet.push_back(it->second);
      }
      for (int i : onFacet) near[i].insert(onFacet.begin(), onFacet.end());
    }
  }
  RecoveryPoints r;
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    const ContactNode& n = nodes[i];
    r.x.push_back({n.x, n.y, n.z});
    r.normal.push_back({n.normal[0], n.normal[1], n.normal[2]});
    r.value.push_back(n.pressure);
    near[i].insert(static_cast<int>(i));
    r.patch.emplace_back(near[i].begin(), near[i].end());
    r.degree.push_back(pairDegree[pairOf[i]]);
  }
  return r;
}

// A node on a symmetry plane has only the half of its ring on the model's side. The model stands
// for the whole body mirrored across the plane, whose ring holds the mirror images as well: they
// join the node's patch as extra points, so the fit is the whole body's and its slope across the
// plane zero. Points on the plane are their own images.
void addMirrorImages(RecoveryPoints& r, const std::vector<ContactNode>& nodes,
                     const ElasticContactProblem& problem) {
  const int dim = problem.dim();
  std::map<int, std::vector<int>> planes;  // slave node -> the components its planes hold
  for (const auto& [node, c] : problem.mirroredComponents) planes[node].push_back(c);
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    const auto it = planes.find(nodes[i].slaveNode);
    if (it == planes.end()) continue;
    const std::vector<int> ring = r.patch[i];
    double scale = 0.0;
    for (int j : ring)
      for (int c = 0; c < dim; ++c) scale = std::max(scale, std::abs(r.x[j][c] - r.x[i][c]));
    for (int j : ring)
      for (const auto& image : mirrorImages(r.x[i], it->second, r.x[j], 1e-9 * scale)) {
        r.patch[i].push_back(static_cast<int>(r.x.size()));
        r.x.push_back(image);
        r.normal.push_back(r.normal[i]);
        r.value.push_back(r.value[j]);
        r.patch.emplace_back();  // an image is not recovered itself
        r.degree.push_back(1);
      }
  }
}

// The slots of the nodal stress averages: one per (body, mesh node), so that a node two bodies
// share (a conforming mesh) averages each body's elements on their own. A node of one body takes
// its own id; a further body's copy takes a slot after the mesh's nodes. Every rank numbers them
// alike (from every subdomain, in order).
struct NodalSlots {
  std::vector<int> firstBody;  // per mesh node: the first body using it, or -1
  std::map<std::pair<int, long long>, int> further;  // (body, node) of a node's further bodies
  std::size_t count = 0;
  std::size_t of(int body, long long node) const {
    return firstBody[node] == body ? static_cast<std::size_t>(node) : further.at({body, node});
  }
};

NodalSlots nodalSlots(const ElasticContactProblem& problem) {
  NodalSlots s;
  s.firstBody.assign(problem.mesh.numNodes(), -1);
  s.count = s.firstBody.size();
  for (std::size_t k = 0; k < problem.subdomains.size(); ++k) {
    const int body = problem.bodyOfSubdomain[problem.subdomains[k].id];
    for (long long g : problem.subdomains[k].globalNode) {
      if (s.firstBody[g] < 0) s.firstBody[g] = body;
      if (s.firstBody[g] != body && s.further.emplace(std::make_pair(body, g), s.count).second)
        ++s.count;
    }
  }
  return s;
}

}  // namespace

void recoverContactPressures(std::vector<ContactNode>& nodes,
                             const ElasticContactProblem& problem) {
  // The old single-pair keys leave ContactNode::pair at -1: their one pair is pairs[0].
  std::vector<int> pairOf;
  for (const ContactNode& n : nodes) pairOf.push_back(std::max(n.pair, 0));
  RecoveryPoints r = facetPatches(nodes, pairOf, problem);
  addMirrorImages(r, nodes, problem);
  const std::vector<double> rec =
      patchRecovery(r.x, r.normal, r.value, r.patch, problem.dim(), r.degree);
  for (std::size_t i = 0; i < nodes.size(); ++i)
    nodes[i].pressureRecovered = nodes[i].pressure > 0.0 ? std::max(0.0, rec[i]) : 0.0;
}

double maxRecoveredPressure(const std::vector<ContactNode>& nodes) {
  double p = 0.0;
  for (const auto& n : nodes) p = std::max(p, n.pressureRecovered);
  return p;
}

double maxNodalVonMises(const tfeti::Comm& comm, const ElasticContactProblem& problem,
                        const std::vector<plasticity::StressField>& stresses) {
  // Per slot: the sum of the element-extrapolated stresses of every element of the body sharing
  // the node (a subdomain's nodal field is their mean over its own elements) and their count.
  constexpr int nv = plasticity::kNumVoigt;
  const NodalSlots slots = nodalSlots(problem);
  std::vector<double> local((nv + 1) * slots.count, 0.0), global(local.size(), 0.0);
  for (std::size_t i = 0; i < stresses.size(); ++i) {
    const plasticity::ElementMesh& em = problem.localElements[i];
    const auto& globalNode = problem.local[i].mesh.globalNode;
    std::vector<int> count(em.numNodes(), 0);
    for (int v : em.connectivity) ++count[v];
    for (int a = 0; a < em.numNodes(); ++a) {
      if (count[a] == 0) continue;
      double* g = &local[(nv + 1) * slots.of(problem.localBody[i], globalNode[a])];
      for (int c = 0; c < nv; ++c) g[c] += count[a] * stresses[i].atNode(a, c);
      g[nv] += count[a];
    }
  }
  Teuchos::reduceAll(comm, Teuchos::REDUCE_SUM, static_cast<int>(local.size()), local.data(),
                     global.data());
  double best = 0.0;
  for (std::size_t k = 0; k < slots.count; ++k) {
    const double* s = &global[(nv + 1) * k];
    if (s[nv] == 0.0) continue;
    double mean[nv];
    for (int c = 0; c < nv; ++c) mean[c] = s[c] / s[nv];
    best = std::max(best, plasticity::vonMises(mean));
  }
  return best;
}

}  // namespace contact
