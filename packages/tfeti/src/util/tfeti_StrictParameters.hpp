#pragma once
// Strict numeric parameters, shared by every package.
//
// Teuchos's XML reader converts numbers leniently ("2.0e11abc" -> 2e11, "nan" or "abc" -> 0,
// "8.5" as an int -> 8, "{0, 2e7 3e7}" -> {0, 2e7}), so a mistyped value becomes a different,
// silently accepted one. Two layers close that:
//  - checkXmlNumbers() reads the raw XML text before Teuchos converts it: every int, double
//    and array of them must be a number in its whole text, finite unless its validator allows
//    otherwise;
//  - NumberValidator (a Teuchos validator on the valid parameter list) checks the type, the
//    range and the array length of the converted value, and documents them in
//    --print-parameters. requireNumbers() gives every numeric entry of a valid list that has no
//    validator a plain "finite number" one, so a new parameter is strict without being listed.
// Errors name the parameter's path (sublist/parameter), the value found and what was expected.
#include <Teuchos_ParameterEntryValidator.hpp>
#include <Teuchos_ParameterList.hpp>
#include <Teuchos_RCP.hpp>
#include <Teuchos_StandardParameterEntryValidators.hpp>

#include <limits>
#include <string>
#include <vector>

namespace tfeti {
namespace strict {

class NumberValidator : public Teuchos::ParameterEntryValidator {
 public:
  enum class Kind { Double, Int, DoubleArray, IntArray };

  explicit NumberValidator(Kind kind) : kind_(kind) {}

  // Range of every value (an array's items): lower/upper bounds, open or closed.
  NumberValidator& greaterThan(double v) { return lower(v, true); }
  NumberValidator& atLeast(double v) { return lower(v, false); }
  NumberValidator& lessThan(double v) { return upper(v, true); }
  NumberValidator& atMost(double v) { return upper(v, false); }
  // Arrays: allowed number of items.
  NumberValidator& length(int n) { return lengthBetween(n, n); }
  NumberValidator& lengthBetween(int lo, int hi);
  // nan and +-inf accepted (no parameter needs it today).
  NumberValidator& allowNonFinite() {
    nonFinite_ = true;
    return *this;
  }

  bool nonFiniteAllowed() const { return nonFinite_; }
  Kind kind() const { return kind_; }
  // "double > 0", "int >= 1", "array of 2 doubles", ...
  std::string describe() const;

  const std::string getXMLTypeName() const override { return "tfetiStrictNumberValidator"; }
  void printDoc(const std::string& docString, std::ostream& out) const override;
  ValidStringsList validStringValues() const override { return Teuchos::null; }
  void validate(const Teuchos::ParameterEntry& entry, const std::string& paramName,
                const std::string& sublistName) const override;

 private:
  NumberValidator& lower(double v, bool open) {
    lo_ = v, loOpen_ = open;
    return *this;
  }
  NumberValidator& upper(double v, bool open) {
    hi_ = v, hiOpen_ = open;
    return *this;
  }
  // Empty when v is allowed, else what is wrong with it.
  std::string checkValue(double v) const;

  Kind kind_;
  double lo_ = -std::numeric_limits<double>::infinity();
  double hi_ = std::numeric_limits<double>::infinity();
  bool loOpen_ = false, hiOpen_ = false, nonFinite_ = false;
  int minLength_ = 0, maxLength_ = std::numeric_limits<int>::max();
};

using Validator = Teuchos::RCP<NumberValidator>;

// Shorthands for the common cases.
Validator finite();       // any finite double
Validator positive();     // double > 0 (moduli, radii, sizes, tolerances)
Validator nonNegative();  // double >= 0
Validator between(double lo, double hi, bool loOpen, bool hiOpen);  // double
Validator count(int min = 1);                                       // int >= min
Validator intBetween(int lo, int hi);
Validator doubles(int length);       // array of `length` finite doubles (0: any length)
Validator positiveInts(int length);  // array of ints >= 1 (0: any length)
// A string parameter that takes one of `names` (an unknown value is an error listing them).
Teuchos::RCP<Teuchos::StringToIntegralParameterEntryValidator<int>> choice(
    const std::vector<std::string>& names);

// "Contact problem/Hertz/Radius 1" from Teuchos's sublist name ("root->Contact
// problem->Hertz") and the parameter's name.
std::string parameterPath(const std::string& sublistName, const std::string& paramName);

// Gives every int, double and array-of-number entry of `valid` (recursively) that has no
// validator a NumberValidator of its type: finite, any value.
void requireNumbers(Teuchos::ParameterList& valid);

// Reads the XML file `file` as text and checks every int/double parameter and array of them
// (whole text a number, finite unless the matching entry of `valid` allows otherwise). Throws
// std::invalid_argument naming the file, the parameter's path, the text and what was expected.
void checkXmlNumbers(const std::string& file, const Teuchos::ParameterList& valid);

}  // namespace strict
}  // namespace tfeti
