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

std::vector<ContactRow> tangentialRows(const ContactRow& normalRow, int dim) {
  const auto& entries = normalRow.entries;
  const std::size_t d = static_cast<std::size_t>(dim);
  for (std::size_t k = 0; k < entries.size(); ++k)
    if (entries.size() % d != 0 || entries[k].node != entries[k - k % d].node ||
        entries[k].component != static_cast<int>(k % d))
      throw std::invalid_argument("tangentialRows: the row of slave node " +
                                  std::to_string(normalRow.slaveNode) + " does not list " +
                                  std::to_string(dim) + " components per node");
  std::vector<ContactRow> out;
  for (const auto& t : tangentBasis(normalRow.normal, dim)) {
    ContactRow row = normalRow;
    row.normal = t;
    row.gap = 0.0;
    for (std::size_t k = 0; k < entries.size(); k += d) {
      double s = 0.0;  // the node's weight: -1 (slave) or N_a (master)
      for (std::size_t c = 0; c < d; ++c) s += entries[k + c].coef * normalRow.normal[c];
      for (std::size_t c = 0; c < d; ++c) row.entries[k + c].coef = s * t[c];
    }
    out.push_back(std::move(row));
  }
  return out;
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
