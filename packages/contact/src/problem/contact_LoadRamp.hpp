#pragma once
// Per-entry load ramps: every prescribed displacement and traction of a nonlinear run may grow
// over its own window of the load factor t instead of with t itself, so that loads can follow
// one another (normal first, tangential second, as a frictional contact's history needs):
//   value(t) = value * clamp((t - start) / (end - start), 0, 1).
// The default window {0, 1} is t itself (exactly: no division), so inputs without ramps keep
// their results bit for bit.
//
// Parameters ("Contact problem"): "Prescribed ramps" and "Traction ramps", {start, end} per entry
// of "Prescribed boundaries" and "Traction boundaries" (2 values per entry; empty: all {0, 1}).
#include <Teuchos_ParameterList.hpp>

#include <string>
#include <vector>

namespace contact {

struct LoadRamp {
  double start = 0.0;
  double end = 1.0;
  bool isDefault() const { return start == 0.0 && end == 1.0; }
  // The share of the entry's value applied at load factor t.
  double factor(double t) const;
};

// Adds "Prescribed ramps" and "Traction ramps" to a validated list.
void addLoadRampParameters(Teuchos::ParameterList& list);

// The ramps of `entries` entries from the parameter `name` of `list` (validated): all {0, 1} when
// the array is empty. Throws std::invalid_argument naming `where`/`name` when the array does not
// hold two values per entry or a window is not 0 <= start < end <= 1.
std::vector<LoadRamp> loadRamps(const Teuchos::ParameterList& list, const std::string& name,
                                std::size_t entries, const std::string& where);

}  // namespace contact
