// Materials per body (contact_Materials.hpp): Hertz's combined modulus against its closed forms,
// the bodies' materials read in the order of "Contact problem/Bodies" from one "Material" or
// from "Materials", and the errors that name a body without a material, a material for no body,
// and a global and a per-body material given together.
#include <Teuchos_UnitTestHarness.hpp>

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "contact_Driver.hpp"
#include "contact_Materials.hpp"

namespace {

using Teuchos::ParameterList;

ParameterList contactInput(const std::string& problem = "elastic_contact") {
  ParameterList p("tfeti_contact");
  p.set("Problem", problem);
  auto& cp = p.sublist("Contact problem");
  cp.set("Mesh file", std::string("two_cylinders.geo"));
  cp.set("Bodies", Teuchos::Array<std::string>(std::vector<std::string>{"cylinder", "block"}));
  cp.set("Subdomains per body", Teuchos::Array<int>(std::vector<int>{2, 2}));
  return p;
}

void setMaterial(ParameterList& m, double E, double nu) {
  m.set("Young's modulus", E);
  m.set("Poisson's ratio", nu);
}

// The message of the error validateDriverParameters throws ("" if none).
std::string validationError(ParameterList p) {
  try {
    contact::validateDriverParameters(p, "input.xml");
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

bool has(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

TEUCHOS_UNIT_TEST(Materials, CombinedModulusClosedForms) {
  const plasticity::ElasticLaw steel(2.1e11, 0.3), aluminium(7e10, 0.33);
  // One body against a rigid obstacle: E / (1 - nu^2).
  TEST_FLOATING_EQUALITY(contact::combinedModulus({steel}), 2.1e11 / 0.91, 1e-14);
  // Two bodies of one material: E / (2 (1 - nu^2)).
  TEST_FLOATING_EQUALITY(contact::combinedModulus({steel, steel}), 2.1e11 / 1.82, 1e-14);
  // Dissimilar: 1 / ((1 - nu1^2)/E1 + (1 - nu2^2)/E2), symmetric in the bodies.
  const double expected = 1.0 / ((1 - 0.09) / 2.1e11 + (1 - 0.1089) / 7e10);
  TEST_FLOATING_EQUALITY(contact::combinedModulus({steel, aluminium}), expected, 1e-14);
  TEST_FLOATING_EQUALITY(contact::combinedModulus({aluminium, steel}), expected, 1e-14);
  TEST_THROW(contact::combinedModulus({}), std::invalid_argument);
}

TEUCHOS_UNIT_TEST(Materials, OneMaterialForEveryBody) {
  ParameterList p = contactInput("nonlinear_contact");
  setMaterial(p.sublist("Material"), 2e11, 0.25);
  p.sublist("Material").set("Yield stress", 8e8);
  contact::validateDriverParameters(p, "input.xml");
  const auto m = contact::bodyMaterials(p);
  TEST_EQUALITY(m.size(), 2u);
  for (const auto& b : m) {
    TEST_EQUALITY(b.elastic.E, 2e11);
    TEST_EQUALITY(b.elastic.nu, 0.25);
    TEST_EQUALITY(b.yieldStress, 8e8);
    TEST_EQUALITY(b.hardening, 0.0);
  }
}

TEUCHOS_UNIT_TEST(Materials, PerBodyInTheOrderOfBodies) {
  ParameterList p = contactInput("nonlinear_contact");
  // Listed in another order than Bodies; the block plastic, the cylinder elastic.
  auto& all = p.sublist("Materials");
  setMaterial(all.sublist("block"), 2.1e11, 0.3);
  all.sublist("block").set("Yield stress", 5e8);
  all.sublist("block").set("Hardening modulus", 1e9);
  setMaterial(all.sublist("cylinder"), 7e10, 0.33);
  contact::validateDriverParameters(p, "input.xml");
  TEST_ASSERT(!p.isSublist("Material"));  // the echo shows each material once
  const auto m = contact::bodyMaterials(p);
  TEST_EQUALITY(m.size(), 2u);
  TEST_EQUALITY(m[0].elastic.E, 7e10);
  TEST_EQUALITY(m[0].elastic.nu, 0.33);
  TEST_EQUALITY(m[0].yieldStress, 0.0);
  TEST_EQUALITY(m[1].elastic.E, 2.1e11);
  TEST_EQUALITY(m[1].yieldStress, 5e8);
  TEST_EQUALITY(m[1].hardening, 1e9);
  // Validating the validated list again (as a caller may) changes nothing.
  contact::validateDriverParameters(p, "input.xml");
  TEST_EQUALITY(contact::bodyMaterials(p)[1].yieldStress, 5e8);
}

TEUCHOS_UNIT_TEST(Materials, ErrorsNameTheBodies) {
  {  // a body without a material
    ParameterList p = contactInput();
    setMaterial(p.sublist("Materials").sublist("cylinder"), 7e10, 0.3);
    const std::string e = validationError(p);
    TEST_ASSERT(has(e, "no material for body \"block\""));
  }
  {  // a material for no body
    ParameterList p = contactInput();
    setMaterial(p.sublist("Materials").sublist("cylinder"), 7e10, 0.3);
    setMaterial(p.sublist("Materials").sublist("block"), 7e10, 0.3);
    setMaterial(p.sublist("Materials").sublist("blok"), 7e10, 0.3);
    const std::string e = validationError(p);
    TEST_ASSERT(has(e, "\"blok\" is not a body") && has(e, "cylinder, block"));
  }
  {  // a global and per-body materials
    ParameterList p = contactInput();
    p.sublist("Material").set("Poisson's ratio", 0.3);
    setMaterial(p.sublist("Materials").sublist("cylinder"), 7e10, 0.3);
    setMaterial(p.sublist("Materials").sublist("block"), 7e10, 0.3);
    const std::string e = validationError(p);
    TEST_ASSERT(has(e, "Material (\"Poisson's ratio\") and Materials") && has(e, "both given"));
  }
  {  // a body's material without Young's modulus, and one out of range
    ParameterList p = contactInput();
    p.sublist("Materials").sublist("cylinder").set("Poisson's ratio", 0.3);
    setMaterial(p.sublist("Materials").sublist("block"), 7e10, 0.3);
    TEST_ASSERT(has(validationError(p), "Materials/cylinder: \"Young's modulus\" is required"));
    setMaterial(p.sublist("Materials").sublist("cylinder"), -7e10, 0.3);
    TEST_ASSERT(has(validationError(p), "Materials/cylinder"));
  }
  {  // a structured problem has one body
    ParameterList p("tfeti_contact");
    p.set("Problem", std::string("elasticity"));
    setMaterial(p.sublist("Materials").sublist("box"), 7e10, 0.3);
    TEST_ASSERT(has(validationError(p), "Problem elasticity has one material"));
  }
}

}  // namespace
