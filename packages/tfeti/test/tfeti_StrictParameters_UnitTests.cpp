// Unit tests of the strict parameter layer: the raw XML text check (whole text a number, finite,
// integers for ints, arrays comma-separated), the range/length/type validator, the path and
// value named in every message, and requireNumbers() on entries without a validator.
#include <Teuchos_Array.hpp>
#include <Teuchos_UnitTestHarness.hpp>

#include <cstdio>
#include <fstream>
#include <functional>
#include <limits>
#include <string>

#include "tfeti_StrictParameters.hpp"
#include "tfeti_TestHelpers.hpp"

namespace {

namespace strict = tfeti::strict;
using Teuchos::Array;
using Teuchos::ParameterList;

using tfeti_test::contains;
using tfeti_test::messageOf;

// A valid list "root" with a sublist "Material" and an array entry.
ParameterList validList() {
  ParameterList pl("root");
  auto& mat = pl.sublist("Material");
  mat.set("Young's modulus", 1.0, "E", strict::positive());
  mat.set("Poisson's ratio", 0.3, "nu", strict::between(-1.0, 0.5, true, true));
  pl.set("Count", 2, "", strict::count());
  pl.set("Pair", Array<double>(2, 0.0), "", strict::doubles(2));
  auto open = Teuchos::rcp(new strict::NumberValidator(strict::NumberValidator::Kind::Double));
  open->allowNonFinite();
  pl.set("Anything", 0.0, "", open);
  pl.set("Free", 1.0, "no validator");
  strict::requireNumbers(pl);
  return pl;
}

// checkXmlNumbers' message for one parameter line inside <ParameterList name="Material">.
std::string xmlMessage(const std::string& parameterLine, bool inMaterial = true) {
  const std::string path = "strict_unit_test.xml";
  {
    std::ofstream f(path);
    f << "<ParameterList name=\"root\">\n";
    if (inMaterial) f << "<ParameterList name=\"Material\">\n";
    f << parameterLine << "\n";
    if (inMaterial) f << "</ParameterList>\n";
    f << "</ParameterList>\n";
  }
  const ParameterList valid = validList();
  const std::string m = messageOf([&] { strict::checkXmlNumbers(path, valid); });
  std::remove(path.c_str());
  return m;
}

TEUCHOS_UNIT_TEST(StrictXml, NumbersInTheirWholeText) {
  const auto p = [](const std::string& type, const std::string& value) {
    return "<Parameter name=\"Young's modulus\" type=\"" + type + "\" value=\"" + value + "\"/>";
  };
  TEST_EQUALITY(xmlMessage(p("double", "2.0e11")), "");
  TEST_EQUALITY(xmlMessage(p("double", " 2.0e11 ")), "");
  for (const char* bad : {"2.0e11abc", "0.3.1", "1e-7e", "abc", "", " ", "1,5", "0x"}) {
    const std::string m = xmlMessage(p("double", bad));
    TEST_ASSERT(contains(
        m, "strict_unit_test.xml: Material/Young's modulus: \"" + std::string(bad) + "\""));
    TEST_ASSERT(contains(m, "expected a finite number"));
  }
  for (const char* bad : {"nan", "-inf", "inf", "1e999", "-1e400"})
    TEST_ASSERT(contains(xmlMessage(p("double", bad)), "not a finite number"));
  TEST_EQUALITY(xmlMessage(p("int", "8")), "");
  const std::string b = xmlMessage("<Parameter name=\"Flag\" type=\"bool\" value=\"maybe\"/>");
  TEST_ASSERT(contains(b, "Material/Flag: \"maybe\" is not a bool"));
  TEST_EQUALITY(xmlMessage("<Parameter name=\"Flag\" type=\"bool\" value=\"true\"/>"), "");
  for (const char* bad : {"8.5", "1e3", "8x", "99999999999"})
    TEST_ASSERT(contains(xmlMessage(p("int", bad)), "expected an integer"));
}

TEUCHOS_UNIT_TEST(StrictXml, Arrays) {
  const auto p = [](const std::string& type, const std::string& value) {
    return "<Parameter name=\"Pair\" type=\"" + type + "\" value=\"" + value + "\"/>";
  };
  TEST_EQUALITY(xmlMessage(p("Array(double)", "{0, -2.0e7}"), false), "");
  TEST_EQUALITY(xmlMessage(p("Array(double)", "{}"), false), "");
  const std::string noComma = xmlMessage(p("Array(double)", "{0, 2e7 3e7}"), false);
  TEST_ASSERT(contains(noComma, "Pair: item 1 \"2e7 3e7\""));
  TEST_ASSERT(contains(noComma, "separated by commas"));
  TEST_ASSERT(contains(xmlMessage(p("Array(double)", "{0, nan}"), false), "not a finite"));
  TEST_ASSERT(contains(xmlMessage(p("Array(double)", "{0, }"), false), "ends with a comma"));
  TEST_ASSERT(contains(xmlMessage(p("Array(double)", "{1,,2}"), false), "item 1 \"\""));
  TEST_ASSERT(contains(xmlMessage(p("Array(double)", "0, 1"), false), "not an array"));
  TEST_ASSERT(contains(xmlMessage(p("Array(int)", "{8, 8.5}"), false), "item 1 \"8.5\""));
  // Strings are not numbers: not checked here.
  TEST_EQUALITY(xmlMessage(p("Array(string)", "{a, b c}"), false), "");
}

TEUCHOS_UNIT_TEST(StrictXml, NonFiniteWhereTheParameterAllowsIt) {
  const auto p = [](const std::string& value) {
    return "<Parameter name=\"Anything\" type=\"double\" value=\"" + value + "\"/>";
  };
  TEST_EQUALITY(xmlMessage(p("inf"), false), "");
  TEST_EQUALITY(xmlMessage(p("nan"), false), "");
  TEST_ASSERT(contains(xmlMessage(p("nanx"), false), "not a number"));
}

TEUCHOS_UNIT_TEST(StrictXml, MalformedXmlNamesTheFile) {
  const std::string path = "strict_unit_test_bad.xml";
  {
    std::ofstream f(path);
    f << "<ParameterList name=\"root\">\n<Parameter name=\"x\" type=\"double\" value=\"1\"\n";
  }
  const std::string m = messageOf([&] { strict::checkXmlNumbers(path, validList()); });
  std::remove(path.c_str());
  TEST_ASSERT(contains(m, path));
}

TEUCHOS_UNIT_TEST(StrictValidator, RangesLengthsTypes) {
  const ParameterList valid = validList();
  const auto check = [&](const std::function<void(ParameterList&)>& set) {
    ParameterList p("root");
    set(p);
    return messageOf([&] { p.validateParametersAndSetDefaults(valid); });
  };
  TEST_EQUALITY(check([](ParameterList& p) { p.sublist("Material").set("Young's modulus", 2e11); }),
                "");
  const std::string e0 =
      check([](ParameterList& p) { p.sublist("Material").set("Young's modulus", 0.0); });
  TEST_ASSERT(contains(e0, "Material/Young's modulus: 0 is out of range; expected double > 0"));
  const std::string nu =
      check([](ParameterList& p) { p.sublist("Material").set("Poisson's ratio", 0.5); });
  TEST_ASSERT(
      contains(nu, "Material/Poisson's ratio: 0.5 is out of range; expected double in (-1, 0.5)"));
  TEST_ASSERT(
      contains(check([](ParameterList& p) { p.sublist("Material").set("Poisson's ratio", -1.0); }),
               "out of range"));
  TEST_EQUALITY(
      check([](ParameterList& p) { p.sublist("Material").set("Poisson's ratio", -0.99); }), "");
  TEST_ASSERT(
      contains(check([](ParameterList& p) { p.set("Count", 0); }), "Count: 0 is out of range"));
  TEST_ASSERT(contains(check([](ParameterList& p) { p.set("Count", 2.0); }),
                       "Count: has type double; expected int"));
  TEST_ASSERT(contains(check([](ParameterList& p) { p.set("Pair", Array<double>(3, 1.0)); }),
                       "Pair: {1, 1, 1} has 3 items; expected an array of 2 doubles"));
  const double inf = std::numeric_limits<double>::infinity();
  TEST_ASSERT(contains(check([&](ParameterList& p) { p.set("Pair", Array<double>(2, -inf)); }),
                       "Pair: item 0 -inf is not finite"));
  // requireNumbers: an entry declared without a validator is still finite and typed.
  TEST_ASSERT(
      contains(check([&](ParameterList& p) { p.set("Free", inf); }), "Free: inf is not finite"));
  TEST_ASSERT(contains(check([&](ParameterList& p) { p.set("Free", std::string("1")); }),
                       "Free: has type string; expected double"));
  TEST_EQUALITY(check([&](ParameterList& p) { p.set("Anything", inf); }), "");
}

TEUCHOS_UNIT_TEST(StrictValidator, DocumentsTypeAndRange) {
  TEST_EQUALITY(strict::positive()->describe(), "double > 0, finite");
  TEST_EQUALITY(strict::count()->describe(), "int >= 1");
  TEST_EQUALITY(strict::between(-1.0, 0.5, true, true)->describe(), "double in (-1, 0.5), finite");
  TEST_EQUALITY(strict::positiveInts(2)->describe(), "array of 2 ints, each >= 1");
  std::ostringstream printed;
  validList().print(printed, ParameterList::PrintOptions().showDoc(true).showTypes(true));
  TEST_ASSERT(contains(printed.str(), "(double > 0, finite)"));
  TEST_ASSERT(contains(printed.str(), "(double any value, finite)"));
}

TEUCHOS_UNIT_TEST(StrictPath, FromTeuchosSublistNames) {
  TEST_EQUALITY(strict::parameterPath("root", "x"), "x");
  TEST_EQUALITY(strict::parameterPath("root->Contact problem->Hertz", "Radius 1"),
                "Contact problem/Hertz/Radius 1");
}

}  // namespace
