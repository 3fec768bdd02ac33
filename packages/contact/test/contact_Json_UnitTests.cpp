// summary.json's numbers (contact_Json.hpp): every double reads back as itself, in the fewest
// digits that do (runs are compared to 1e-10 and below from these files), non-finite as null.
#include <Teuchos_UnitTestHarness.hpp>

#include <cmath>
#include <cstdlib>
#include <limits>
#include <string>

#include "contact_Json.hpp"

namespace {

// The text of one number as summary.json writes it.
std::string written(double x) {
  contact::Json j = contact::Json::object();
  j["x"] = x;
  const std::string text = j.dump(0);
  const auto colon = text.find(':');
  const auto end = text.find_first_of(",}\n", colon);
  std::string value = text.substr(colon + 1, end - colon - 1);
  value.erase(0, value.find_first_not_of(' '));
  return value;
}

TEUCHOS_UNIT_TEST(Json, NumbersReadBackExactly) {
  const double values[] = {1.0 / 3.0,
                           0.1 + 0.2,
                           2.162750353e-4 * (1.0 + 3e-15),
                           -1.0616342475612345e9,
                           std::nextafter(1.0, 2.0),
                           std::numeric_limits<double>::min(),
                           std::numeric_limits<double>::denorm_min(),
                           std::numeric_limits<double>::max()};
  for (double x : values) {
    const std::string text = written(x);
    out << x << " -> " << text << "\n";
    TEST_EQUALITY(std::strtod(text.c_str(), nullptr), x);
  }
}

TEUCHOS_UNIT_TEST(Json, ShortestDigitsKept) {
  // Input values and round figures stay as typed, not 0.29999999999999999.
  TEST_EQUALITY(written(0.3), "0.3");
  TEST_EQUALITY(written(2e11), "200000000000");
  TEST_EQUALITY(written(1e-9), "1e-09");
  TEST_EQUALITY(written(125000.0), "125000");
  TEST_EQUALITY(written(-0.5), "-0.5");
}

TEUCHOS_UNIT_TEST(Json, NonFiniteIsNull) {
  TEST_EQUALITY(written(std::numeric_limits<double>::quiet_NaN()), "null");
  TEST_EQUALITY(written(std::numeric_limits<double>::infinity()), "null");
}

}  // namespace
