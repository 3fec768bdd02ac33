// The mortar masters (contact_Mortar.hpp): the weighted-gap rows of a slave surface against a
// mesh surface or a rigid obstacle, in the common row form.
#include <algorithm>
#include <cmath>
#include <set>
#include <stdexcept>

#include "contact_Mortar.hpp"
#include "contact_MortarIntegration.hpp"

namespace contact {

namespace {

std::vector<double> configuration(const std::vector<double>& coords, const std::vector<double>& u) {
  if (u.empty()) return coords;
  if (u.size() != coords.size())
    throw std::invalid_argument(
        "mortar: the displacement must be empty or hold one value per "
        "coordinate");
  std::vector<double> x(coords);
  for (std::size_t i = 0; i < x.size(); ++i) x[i] += u[i];
  return x;
}

// Row of multiplier node j from its coupling: entries of node j first, then the other slave
// nodes, then the master nodes, dim components each; coefficients and gap divided by W_j.
// `normal` is the row's n (pointing from the master towards the slave).
ContactRow mortarRow(int dim, int j, const MortarCoupling& c, const std::array<double, 3>& normal,
                     double weightedGap, const std::vector<double>& x) {
  ContactRow row;
  row.slaveNode = j;
  row.normal = normal;
  row.weight = c.weight;
  row.gap = weightedGap / c.weight;
  for (int k = 0; k < dim; ++k)
    row.point[k] = x[static_cast<std::size_t>(dim) * j + k] - row.gap * normal[k];
  auto add = [&](int node, double s) {
    for (int k = 0; k < dim; ++k) row.entries.push_back({node, k, s * normal[k]});
  };
  const auto own = c.slave.find(j);
  add(j, -(own == c.slave.end() ? 0.0 : own->second) / c.weight);
  // Entries at rounding level (D's off-diagonal terms, which biorthogonality makes zero, and a
  // master node the dual function barely sees) only cost the dual operator nonzeros.
  const double tiny = 1e-13 * c.weight;
  for (const auto& [a, d] : c.slave)
    if (a != j && std::abs(d) > tiny) add(a, -d / c.weight);
  for (const auto& [k, m] : c.master)
    if (std::abs(m) > tiny) add(k, m / c.weight);
  return row;
}

class MeshMortarMaster : public ContactMaster {
 public:
  MeshMortarMaster(MortarSurface s, MortarSurface m, const ContactSearchOptions& o)
      : slave_(std::move(s)), master_(std::move(m)), o_(o) {
    validateSearchOptions(o_, "mortar contact");
    if (slave_.dim != master_.dim)
      throw std::invalid_argument(
          "mortar contact: the slave and master surfaces differ in "
          "dimension");
  }
  int dimension() const override { return slave_.dim; }
  std::vector<int> masterNodes() const override {
    std::set<int> s(master_.facets.begin(), master_.facets.end());
    return {s.begin(), s.end()};
  }

  ContactRowsResult rows(const std::vector<double>& coords, const std::vector<int>& slaveNodes,
                         const std::vector<double>& u) const override {
    const int dim = slave_.dim;
    const std::vector<double> x = configuration(coords, u);
    const MortarCouplings c = mortarCouplings(x, slave_, master_, o_.searchRadius);
    const auto normals = slaveNodalNormals(x, slave_);
    const auto full = fullMultiplierWeights(x, slave_);
    ContactRowsResult result;
    result.candidatePairs = c.candidatePairs;
    result.allPairs = static_cast<long long>(slave_.numFacets()) * master_.numFacets();
    for (int j : slaveNodes) {
      const auto it = c.byNode.find(j);
      const auto fw = full.find(j);
      if (fw == full.end()) continue;  // not on the slave surface
      if (it == c.byNode.end() || !(it->second.weight > kMortarMinShare * fw->second)) {
        ++result.beyondRadius;
        continue;
      }
      const MortarCoupling& cj = it->second;
      const auto& nj = normals.at(j);
      // g~_j = n_j . (sum_k M_jk x_k - sum_a D_ja x_a)
      double g = 0.0;
      for (const auto& [k, m] : cj.master)
        for (int q = 0; q < dim; ++q) g += m * nj[q] * x[static_cast<std::size_t>(dim) * k + q];
      for (const auto& [a, d] : cj.slave)
        for (int q = 0; q < dim; ++q) g -= d * nj[q] * x[static_cast<std::size_t>(dim) * a + q];
      const std::array<double, 3> n{-nj[0], -nj[1], -nj[2]};
      result.rows.push_back(mortarRow(dim, j, cj, n, g, x));
    }
    return result;
  }

 private:
  MortarSurface slave_, master_;
  ContactSearchOptions o_;
};

class ObstacleMortarMaster : public ContactMaster {
 public:
  ObstacleMortarMaster(MortarSurface s, const RigidObstacle& b, const ContactSearchOptions& o)
      : slave_(std::move(s)), b_(b), o_(o) {
    b_.validate();
    validateSearchOptions(o_, "mortar contact with a rigid obstacle");
    if (b_.dim != slave_.dim)
      throw std::invalid_argument(
          "mortar contact: the rigid obstacle's dimension differs from "
          "the slave surface's");
  }
  int dimension() const override { return slave_.dim; }
  std::vector<int> masterNodes() const override { return {}; }

  ContactRowsResult rows(const std::vector<double>& coords, const std::vector<int>& slaveNodes,
                         const std::vector<double>& u) const override {
    const int dim = slave_.dim;
    const std::vector<double> x = configuration(coords, u);
    const MultiplierSpace lm = multiplierSpace(slave_.type);
    const PlaneQuadrature q = referenceFacetQuadrature(slave_.type);
    const int np = slave_.nodesPerFacet(), nq = static_cast<int>(q.weights.size());
    // Every quadrature point of the slave surface as a point of its own (reference position and
    // displacement interpolated), so that the obstacle's gap there is computed exactly as at a
    // node, height functions read at the reference position included.
    std::vector<double> ref, disp, w, Nl, Ns;
    double N[9], L[9];
    for (int e = 0; e < slave_.numFacets(); ++e) {
      const int* nodes = slave_.facets.data() + static_cast<std::size_t>(e) * np;
      const FacetGeometry f{dim, slave_.type, nodes, &x};
      for (int k = 0; k < nq; ++k) {
        facetShapeFunctions(slave_.type, q.points[k].data(), N, nullptr);
        multiplierShapeFunctions(lm, q.points[k].data(), L);
        for (int c = 0; c < dim; ++c) {
          double r = 0.0, d = 0.0;
          for (int a = 0; a < np; ++a) {
            const std::size_t i = static_cast<std::size_t>(dim) * nodes[a] + c;
            r += N[a] * coords[i];
            if (!u.empty()) d += N[a] * u[i];
          }
          ref.push_back(r), disp.push_back(d);
        }
        w.push_back(q.weights[k] * f.jacobian(q.points[k].data()));
        Nl.insert(Nl.end(), L, L + lm.count);
        Ns.insert(Ns.end(), N, N + np);
      }
    }
    std::vector<int> points(w.size());
    for (std::size_t i = 0; i < points.size(); ++i) points[i] = static_cast<int>(i);
    const ContactRowsResult atPoints =
        computeObstacleRows(b_, ref, points, o_, u.empty() ? std::vector<double>() : disp);
    // A point beyond the search radius is open by at least the radius.
    std::vector<double> gap(w.size(), o_.searchRadius);
    for (const auto& r : atPoints.rows) gap[r.slaveNode] = r.gap;
    // Per facet the dual basis on the whole facet; W_j, D_ja and int phi_j g.
    std::map<int, MortarCoupling> coupling;
    std::map<int, double> gapIntegral;
    double phi[9];
    for (int e = 0; e < slave_.numFacets(); ++e) {
      const int* nodes = slave_.facets.data() + static_cast<std::size_t>(e) * np;
      const std::size_t q0 = static_cast<std::size_t>(e) * nq;
      const std::vector<double> we(w.begin() + q0, w.begin() + q0 + nq);
      const std::vector<double> le(Nl.begin() + q0 * lm.count, Nl.begin() + (q0 + nq) * lm.count);
      const std::vector<double> A = dualBasisCoefficients(lm.count, we, le);
      if (A.empty())
        throw std::invalid_argument("mortar: slave facet " + std::to_string(e) +
                                    " has no dual basis (a degenerate facet)");
      for (int k = 0; k < nq; ++k) {
        const std::size_t p = q0 + k;
        for (int j = 0; j < lm.count; ++j) {
          phi[j] = 0.0;
          for (int b = 0; b < lm.count; ++b) phi[j] += A[j * lm.count + b] * Nl[p * lm.count + b];
          MortarCoupling& c = coupling[nodes[j]];
          const double wp = w[p] * phi[j];
          for (int a = 0; a < np; ++a) c.slave[nodes[a]] += wp * Ns[p * np + a];
          c.weight += wp;
          gapIntegral[nodes[j]] += wp * gap[p];
        }
      }
    }
    // The row's normal: the obstacle's at the node (its own row); nodes beyond the radius or
    // (height function) missing the obstacle get no row.
    const ContactRowsResult atNodes = computeObstacleRows(b_, coords, slaveNodes, o_, u);
    ContactRowsResult result;
    result.allPairs = result.candidatePairs = static_cast<long long>(slaveNodes.size());
    for (const auto& nodeRow : atNodes.rows) {
      const auto it = coupling.find(nodeRow.slaveNode);
      if (it == coupling.end()) continue;  // not a multiplier node
      if (!(it->second.weight > 0.0)) {
        ++result.beyondRadius;
        continue;
      }
      ContactRow row = mortarRow(dim, nodeRow.slaveNode, it->second, nodeRow.normal,
                                 gapIntegral.at(nodeRow.slaveNode), x);
      row.point = nodeRow.point;
      result.rows.push_back(std::move(row));
    }
    result.beyondRadius += atNodes.beyondRadius;
    return result;
  }

 private:
  MortarSurface slave_;
  RigidObstacle b_;
  ContactSearchOptions o_;
};

}  // namespace

std::unique_ptr<ContactMaster> makeMortarMaster(MortarSurface slave, MortarSurface master,
                                                const ContactSearchOptions& options) {
  return std::make_unique<MeshMortarMaster>(std::move(slave), std::move(master), options);
}

std::unique_ptr<ContactMaster> makeMortarObstacleMaster(MortarSurface slave,
                                                        const RigidObstacle& obstacle,
                                                        const ContactSearchOptions& options) {
  return std::make_unique<ObstacleMortarMaster>(std::move(slave), obstacle, options);
}

}  // namespace contact
