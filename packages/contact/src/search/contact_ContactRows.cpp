#include "contact_ContactRows.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace contact {

void validateSearchOptions(const ContactSearchOptions& options, const char* who) {
  if (!(options.searchRadius > 0.0) || !std::isfinite(options.searchRadius))
    throw std::invalid_argument(std::string(who) + ": searchRadius must be positive and finite");
  if (!(options.endTolerance >= 0.0))
    throw std::invalid_argument(std::string(who) + ": endTolerance must be >= 0");
  if (options.maxNewtonIterations < 1)
    throw std::invalid_argument(std::string(who) + ": maxNewtonIterations must be >= 1");
}

tfeti::InequalityRow toInequalityRow(const ContactRow& row,
                                     const std::function<std::pair<int, int>(int, int)>& dofOf) {
  tfeti::InequalityRow out;
  out.gap = row.gap;
  // The slave node's normal row; its tangential rows add 1 and 2 (tangentialKey).
  out.key = row.slaveNode >= 0 ? kRowsPerSlaveNode * static_cast<long long>(row.slaveNode) : -1;
  for (const NodeEntry& e : row.entries) {
    // The dual operator's cost grows with B's nonzeros; the zeros only served a fixed pattern.
    if (e.coef == 0.0) continue;
    const auto [subdomain, dof] = dofOf(e.node, e.component);
    out.entries.push_back({subdomain, dof, e.coef});
  }
  return out;
}

long long tangentialKey(const tfeti::InequalityRow& normal, std::size_t j) {
  return normal.key < 0 ? -1 : normal.key + 1 + static_cast<long long>(j);
}

}  // namespace contact
