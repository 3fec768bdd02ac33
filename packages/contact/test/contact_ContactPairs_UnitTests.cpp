// Contact pairs (contact_ContactPairs.hpp): the old single-pair keys read as one unnamed pair,
// "Contact pairs" read in input order with each pair's own keys, a list validated twice staying
// the same, and the errors that name the pair and the parameter: old keys beside Contact pairs,
// an unknown key in a pair, no Slave, neither or both of Master and Rigid obstacle, the same
// pair twice, pairs of different contact types, and each pair's discretization.
#include <Teuchos_UnitTestHarness.hpp>

#include <stdexcept>
#include <string>
#include <vector>

#include "contact_ContactPairs.hpp"
#include "contact_Driver.hpp"

namespace {

using Teuchos::ParameterList;

ParameterList contactInput() {
  ParameterList p("tfeti_contact");
  p.set("Problem", std::string("elastic_contact"));
  auto& cp = p.sublist("Contact problem");
  cp.set("Mesh file", std::string("ball.geo"));
  cp.set("Bodies", Teuchos::Array<std::string>(std::vector<std::string>{"ball", "plate"}));
  cp.set("Subdomains per body", Teuchos::Array<int>(std::vector<int>{1, 1}));
  return p;
}

ParameterList& addPair(ParameterList& p, const std::string& name, const std::string& slave,
                       const std::string& master) {
  auto& pair = p.sublist("Contact problem").sublist("Contact pairs").sublist(name);
  pair.set("Slave", slave);
  if (!master.empty()) pair.set("Master", master);
  return pair;
}

void addPlane(ParameterList& pair) {
  auto& ro = pair.sublist("Rigid obstacle");
  ro.set("Type", std::string("plane"));
  ro.set("Point", Teuchos::Array<double>(std::vector<double>{0, 0, -1}));
  ro.set("Normal", Teuchos::Array<double>(std::vector<double>{0, 0, 1}));
}

// The message of the error validating and reading the pairs throws ("" if none).
std::string pairsError(ParameterList p) {
  try {
    contact::validateDriverParameters(p, "input.xml");
    contact::contactPairSpecs(p);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

bool has(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

TEUCHOS_UNIT_TEST(ContactPairs, OldKeysAreOneUnnamedPair) {
  ParameterList p = contactInput();
  p.sublist("Contact problem").set("Slave", std::string("ball_surface"));
  p.sublist("Contact problem").set("Master", std::string("plate_top"));
  p.sublist("Contact problem").set("Search radius", 0.5);
  contact::validateDriverParameters(p, "input.xml");
  TEST_ASSERT(!p.sublist("Contact problem").isSublist("Contact pairs"));
  const auto pairs = contact::contactPairSpecs(p);
  TEST_EQUALITY(pairs.size(), 1u);
  TEST_EQUALITY(pairs[0].name, "");
  TEST_EQUALITY(pairs[0].where, "Contact problem");
  TEST_EQUALITY(pairs[0].slave, "ball_surface");
  TEST_EQUALITY(pairs[0].master, "plate_top");
  TEST_EQUALITY(pairs[0].searchRadius, 0.5);
  TEST_EQUALITY(pairs[0].discretization, "node_to_segment");
  TEST_ASSERT(!pairs[0].obstacle);
}

TEUCHOS_UNIT_TEST(ContactPairs, NamedPairsInInputOrder) {
  ParameterList p = contactInput();
  addPair(p, "upper", "ball_surface", "plate_bottom").set("Search radius", 0.25);
  addPlane(addPair(p, "floor", "ball_surface", ""));
  contact::validateDriverParameters(p, "input.xml");
  // Validating the validated list again (tfeti_contact, then ContactSolver::setParameters)
  // accepts it and gives the same pairs.
  ParameterList again = p;
  contact::validateDriverParameters(again, "input.xml");
  for (const ParameterList* list : {&p, &again}) {
    const auto pairs = contact::contactPairSpecs(*list);
    TEST_EQUALITY(pairs.size(), 2u);
    TEST_EQUALITY(pairs[0].name, "upper");
    TEST_EQUALITY(pairs[0].where, "Contact problem/Contact pairs/upper");
    TEST_EQUALITY(pairs[0].master, "plate_bottom");
    TEST_EQUALITY(pairs[0].searchRadius, 0.25);
    TEST_EQUALITY(pairs[1].name, "floor");
    TEST_ASSERT(pairs[1].master.empty());
    TEST_ASSERT(pairs[1].obstacle.has_value());
    TEST_EQUALITY(pairs[1].obstacle->point[2], -1.0);
    TEST_EQUALITY(pairs[1].searchRadius, 0.0);
    TEST_EQUALITY(pairs[1].contactType, "frictionless");
  }
}

TEUCHOS_UNIT_TEST(ContactPairs, ErrorsNameThePairAndParameter) {
  {  // an old key beside Contact pairs
    ParameterList p = contactInput();
    addPair(p, "upper", "ball_surface", "plate_bottom");
    p.sublist("Contact problem").set("Master", std::string("plate_bottom"));
    const std::string e = pairsError(p);
    out << e << "\n";
    TEST_ASSERT(has(e, "\"Contact pairs\" (\"upper\") and the single-pair key \"Master\""));
  }
  {  // an unknown key in a pair
    ParameterList p = contactInput();
    addPair(p, "upper", "ball_surface", "plate_bottom").set("Slave radius", 1.0);
    const std::string e = pairsError(p);
    TEST_ASSERT(has(e, "Contact problem/Contact pairs/upper") && has(e, "Slave radius"));
  }
  {  // no Slave
    ParameterList p = contactInput();
    addPair(p, "upper", "", "plate_bottom");
    TEST_ASSERT(has(pairsError(p), "Contact pairs/upper: \"Slave\" is required"));
  }
  {  // neither Master nor Rigid obstacle, and both
    ParameterList p = contactInput();
    addPair(p, "upper", "ball_surface", "");
    TEST_ASSERT(has(pairsError(p), "Contact pairs/upper: neither \"Master\" nor"));
    addPlane(addPair(p, "upper", "ball_surface", "plate_bottom"));
    TEST_ASSERT(has(pairsError(p),
                    "Contact pairs/upper: \"Master\" = \"plate_bottom\" and a "
                    "\"Rigid obstacle\" are both given"));
  }
  {  // the same pair twice; the same slave against two obstacles is allowed (a corner)
    ParameterList p = contactInput();
    addPair(p, "one", "ball_surface", "plate_bottom");
    addPair(p, "two", "ball_surface", "plate_bottom");
    TEST_ASSERT(has(pairsError(p), "Contact pairs/two: the same pair as \"one\""));
    ParameterList corner = contactInput();
    addPlane(addPair(corner, "one", "ball_surface", ""));
    addPlane(addPair(corner, "two", "ball_surface", ""));
    TEST_EQUALITY(pairsError(corner), "");
  }
  {  // a tied pair beside a frictionless one
    ParameterList p = contactInput();
    addPair(p, "one", "ball_surface", "plate_bottom");
    addPair(p, "two", "ball_surface", "plate_top").set("Contact type", std::string("tied"));
    TEST_ASSERT(has(pairsError(p), "Contact pairs/two: \"Contact type\" = tied but pair \"one\""));
  }
  {  // each pair keeps its own discretization
    ParameterList p = contactInput();
    addPair(p, "one", "ball_surface", "plate_bottom")
        .set("Contact discretization", std::string("mortar"));
    addPair(p, "two", "ball_surface", "plate_top");
    contact::validateDriverParameters(p, "input.xml");
    const auto pairs = contact::contactPairSpecs(p);
    TEST_EQUALITY(pairs[0].discretization, std::string("mortar"));
    TEST_EQUALITY(pairs[1].discretization, std::string("node_to_segment"));
  }
}

}  // namespace
