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
  // t1 = e_k x n with e_k the axis least aligned with n (never parallel to it), normalized;
  // t2 = n x t1 completes the right-handed basis (t1, t2, n).
  int k = 0;
  for (int c = 1; c < 3; ++c)
    if (std::abs(n[c]) < std::abs(n[k])) k = c;
  std::array<double, 3> e{0.0, 0.0, 0.0};
  e[k] = 1.0;
  std::array<double, 3> t1{e[1] * n[2] - e[2] * n[1], e[2] * n[0] - e[0] * n[2],
                           e[0] * n[1] - e[1] * n[0]};
  const double len = std::sqrt(t1[0] * t1[0] + t1[1] * t1[1] + t1[2] * t1[2]);
  for (double& v : t1) v /= len;
  const std::array<double, 3> t2{n[1] * t1[2] - n[2] * t1[1], n[2] * t1[0] - n[0] * t1[2],
                                 n[0] * t1[1] - n[1] * t1[0]};
  return {t1, t2};
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
