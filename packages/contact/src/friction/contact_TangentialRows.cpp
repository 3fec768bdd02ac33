#include "contact_TangentialRows.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace contact {

std::vector<std::array<double, 3>> tangentBasis(const std::array<double, 3>& n, int dim) {
  if (dim == 2) return {{-n[1], n[0], 0.0}};
  if (dim != 3)
    throw std::invalid_argument("tangentBasis: dimension " + std::to_string(dim) +
                                " (expected 2 or 3)");
  // The frame of Duff et al. (2017, "Building an orthonormal basis, revisited"): a smooth
  // function of n on each half-space n_z >= 0 and n_z < 0, so nearby normals (a node's averaged
  // normal at a kink, or the same normal up to rounding) get nearby frames; it has no branch on
  // which axis is least aligned with n, which flips where two components of n are equal in
  // magnitude. Its one seam is n_z = 0 (-0 counts as >= 0), away from the contact normals of a
  // body pressed along z. Right-handed: t1 x t2 = n.
  const double s = n[2] >= 0.0 ? 1.0 : -1.0;
  const double a = -1.0 / (s + n[2]), b = n[0] * n[1] * a;
  return {{1.0 + s * n[0] * n[0] * a, s * b, -s * n[0]}, {b, s + n[1] * n[1] * a, -n[1]}};
}

namespace {

// A direction counts as held when the row's weight on nodes not held in it is at most this
// fraction of the row's weight (frictionTangentialRows).
constexpr double kHeldWeightTolerance = 0.05;

void requireComponentsPerNode(const ContactRow& normalRow, int dim) {
  const auto& entries = normalRow.entries;
  const std::size_t d = static_cast<std::size_t>(dim);
  for (std::size_t k = 0; k < entries.size(); ++k)
    if (entries.size() % d != 0 || entries[k].node != entries[k - k % d].node ||
        entries[k].component != static_cast<int>(k % d))
      throw std::invalid_argument("tangentialRows: the row of slave node " +
                                  std::to_string(normalRow.slaveNode) + " does not list " +
                                  std::to_string(dim) + " components per node");
}

// The weight of the node whose entries start at k: -1 (slave) or N_a (master).
double nodeWeight(const ContactRow& normalRow, std::size_t k, std::size_t d) {
  double s = 0.0;
  for (std::size_t c = 0; c < d; ++c) s += normalRow.entries[k + c].coef * normalRow.normal[c];
  return s;
}

// The normal row with the normal replaced by the tangent t.
ContactRow rowAlong(const ContactRow& normalRow, const std::array<double, 3>& t, int dim) {
  const std::size_t d = static_cast<std::size_t>(dim);
  ContactRow row = normalRow;
  row.normal = t;
  row.gap = 0.0;
  for (std::size_t k = 0; k < normalRow.entries.size(); k += d) {
    const double s = nodeWeight(normalRow, k, d);
    for (std::size_t c = 0; c < d; ++c) row.entries[k + c].coef = s * t[c];
  }
  return row;
}

}  // namespace

std::vector<ContactRow> tangentialRows(const ContactRow& normalRow, int dim) {
  requireComponentsPerNode(normalRow, dim);
  std::vector<ContactRow> out;
  for (const auto& t : tangentBasis(normalRow.normal, dim))
    out.push_back(rowAlong(normalRow, t, dim));
  return out;
}

std::vector<ContactRow> frictionTangentialRows(const ContactRow& normalRow, int dim,
                                               const HeldComponent& held,
                                               const HeldComponent& mirrored) {
  requireComponentsPerNode(normalRow, dim);
  const std::size_t d = static_cast<std::size_t>(dim);
  const auto& n = normalRow.normal;
  // The tangent-plane directions in which every weighted node of the row is held, orthonormal.
  std::vector<std::array<double, 3>> locked;
  for (int c = 0; c < dim; ++c) {
    // The weight of the row on nodes not held in c, relative to the whole: 0 when the closest
    // point is on a held edge of the master, a little more when the deformed normal tilts it
    // off that edge (1e-5 seen), which would leave a row that is nearly redundant.
    double free = 0.0, total = 0.0;
    for (std::size_t k = 0; k < normalRow.entries.size(); k += d) {
      const double w = std::abs(nodeWeight(normalRow, k, d));
      total += w;
      if (!held(normalRow.entries[k].node, c)) free += w;
    }
    // On a symmetry plane the master's weights do not matter: a dual mortar row spreads 5-6 %
    // of its weight onto off-plane master nodes with both signs, which left a row within 5 % of
    // the symmetry rows' span and the preconditioner's scaling group nearly singular.
    const bool onMirror = mirrored && mirrored(normalRow.slaveNode, c);
    if (!(total > 0.0) || !held(normalRow.slaveNode, c) ||
        (!onMirror && free > kHeldWeightTolerance * total))
      continue;
    std::array<double, 3> v{0.0, 0.0, 0.0};
    v[c] = 1.0;
    for (int i = 0; i < 3; ++i) v[i] -= n[c] * n[i];
    for (const auto& q : locked) {
      const double vq = v[0] * q[0] + v[1] * q[1] + v[2] * q[2];
      for (int i = 0; i < 3; ++i) v[i] -= vq * q[i];
    }
    const double len = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    if (!(len > 0.1)) continue;
    for (auto& x : v) x /= len;
    locked.push_back(v);
  }
  if (locked.empty()) return tangentialRows(normalRow, dim);
  if (static_cast<int>(locked.size()) >= dim - 1) return {};
  // 3D with one locked direction q: the free tangent n x q.
  const auto& q = locked.front();
  std::array<double, 3> t{n[1] * q[2] - n[2] * q[1], n[2] * q[0] - n[0] * q[2],
                          n[0] * q[1] - n[1] * q[0]};
  const double len = std::sqrt(t[0] * t[0] + t[1] * t[1] + t[2] * t[2]);
  for (auto& x : t) x /= len;
  return {rowAlong(normalRow, t, dim)};
}

double applyRow(const ContactRow& row, int dim, const std::vector<double>& displacement) {
  double v = 0.0;
  for (const auto& e : row.entries) {
    const std::size_t i = static_cast<std::size_t>(dim) * e.node + e.component;
    if (i >= displacement.size())
      throw std::invalid_argument("applyRow: node " + std::to_string(e.node) +
                                  " beyond the displacement's " +
                                  std::to_string(displacement.size()) + " values");
    v += e.coef * displacement[i];
  }
  return v;
}

}  // namespace contact
