#include "contact_LoadRamp.hpp"

#include <algorithm>
#include <sstream>
#include <stdexcept>

#include "tfeti_StrictParameters.hpp"

namespace contact {

double LoadRamp::factor(double t) const {
  if (isDefault()) return t;  // today's proportional loading, unchanged to the last bit
  return std::clamp((t - start) / (end - start), 0.0, 1.0);
}

void addLoadRampParameters(Teuchos::ParameterList& list) {
  list.set("Prescribed ramps", Teuchos::Array<double>(),
           "{start, end} load-factor window per Prescribed boundaries entry (2 values each; "
           "empty: {0, 1} for all): the value times clamp((t - start)/(end - start), 0, 1), "
           "0 <= start < end <= 1 (nonlinear_contact: e.g. normal loading first, tangential "
           "second)",
           tfeti::strict::doubles(0));
  list.set("Traction ramps", Teuchos::Array<double>(),
           "{start, end} load-factor window per Traction boundaries entry (2 values each; empty: "
           "{0, 1} for all), as Prescribed ramps",
           tfeti::strict::doubles(0));
}

std::vector<LoadRamp> loadRamps(const Teuchos::ParameterList& list, const std::string& name,
                                std::size_t entries, const std::string& where) {
  const auto values = list.get<Teuchos::Array<double>>(name);
  std::vector<LoadRamp> ramps(entries);
  if (values.empty()) return ramps;
  const std::string path = where + "/" + name;
  if (static_cast<std::size_t>(values.size()) != 2 * entries)
    throw std::invalid_argument(path + ": " + std::to_string(values.size()) +
                                " values; it needs {start, end} for each of the " +
                                std::to_string(entries) + " entries (" +
                                std::to_string(2 * entries) + " values) or none");
  for (std::size_t k = 0; k < entries; ++k) {
    const LoadRamp r{values[2 * k], values[2 * k + 1]};
    if (!(0.0 <= r.start && r.start < r.end && r.end <= 1.0)) {
      std::ostringstream s;
      s << path << ": entry " << k + 1 << " has {" << r.start << ", " << r.end
        << "}; a load-factor window needs 0 <= start < end <= 1";
      throw std::invalid_argument(s.str());
    }
    ramps[k] = r;
  }
  return ramps;
}

}  // namespace contact
