// The friction state handed from load step to load step (contact_FrictionHistory.hpp): the
// accumulated slip (path length and signed sum over the steps that end with the node closed),
// kept for nodes that lose their row, the restart file's round trip bit for bit, and the errors
// naming the file (missing: a restart of a frictionless run; wrong header; truncated). Serial.
#include <Teuchos_UnitTestHarness.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "contact_FrictionHistory.hpp"

namespace {

contact::ContactNode node(int id, int state, double slip) {
  contact::ContactNode n{};
  n.slaveNode = id;
  n.frictionState = state;
  n.slip = slip;
  return n;
}

bool throwsNaming(const std::function<void()>& f, const std::string& what,
                  Teuchos::FancyOStream& out) {
  try {
    f();
  } catch (const std::runtime_error& e) {
    out << "error: " << e.what() << "\n";
    return std::string(e.what()).find(what) != std::string::npos;
  }
  return false;
}

TEUCHOS_UNIT_TEST(FrictionHistory, AccumulatesClosedNodes) {
  std::map<int, contact::AccumulatedSlip> committed;
  // Step 1: node 1 slips by +2, node 2 sticks (a rounding-level slip), node 3 is open (its
  // tangential motion is no slip).
  std::vector<contact::ContactNode> step{node(1, 2, 2.0), node(2, 1, -1e-15), node(3, 0, 5.0)};
  contact::addAccumulatedSlip(step, committed);
  TEST_EQUALITY(step[0].accumulatedSlip, 2.0);
  TEST_EQUALITY(step[0].netSlip, 2.0);
  TEST_EQUALITY(step[1].accumulatedSlip, 1e-15);
  TEST_EQUALITY(step[1].netSlip, -1e-15);
  TEST_EQUALITY(step[2].accumulatedSlip, 0.0);
  TEST_EQUALITY(step[2].netSlip, 0.0);
  // Evaluating does not commit: a rejected or repeated evaluation leaves the sums alone.
  TEST_ASSERT(committed.empty());
  contact::commitAccumulatedSlip(committed, step);
  // Step 2: node 1 slips back by 0.5 (path 2.5, net 1.5), node 3 closes and slips by -1, node 2
  // has lost its row (outside the search radius): its sums are kept.
  std::vector<contact::ContactNode> next{node(1, 2, -0.5), node(3, 2, -1.0)};
  contact::addAccumulatedSlip(next, committed);
  TEST_EQUALITY(next[0].accumulatedSlip, 2.5);
  TEST_EQUALITY(next[0].netSlip, 1.5);
  TEST_EQUALITY(next[1].accumulatedSlip, 1.0);
  TEST_EQUALITY(next[1].netSlip, -1.0);
  contact::commitAccumulatedSlip(committed, next);
  TEST_EQUALITY(committed.size(), 3u);
  TEST_EQUALITY(committed.at(2).path, 1e-15);
  TEST_EQUALITY(committed.at(1).path, 2.5);
  // The path is never below |net|.
  for (const auto& [id, a] : committed) TEST_ASSERT(a.path >= std::abs(a.net));
}

TEUCHOS_UNIT_TEST(FrictionHistory, RestartRoundTrip) {
  const std::string dir =
      (std::filesystem::temp_directory_path() / "contact_friction_history_test").string();
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  contact::FrictionHistory h;
  h.slip[7] = {0.1 + 0.2, -1.0 / 3.0};
  h.slip[9] = {2.5e-7, 2.5e-7};
  h.bounds[7] = 1.234567890123456789e6;
  h.bounds[11] = 0.0;  // a Coulomb bound of an open node, with no slip record
  contact::writeFrictionRestart(dir, h);
  const contact::FrictionHistory r = contact::readFrictionRestart(dir);
  TEST_EQUALITY(r.slip.size(), 3u);  // every node of either map
  TEST_EQUALITY(r.slip.at(7).path, h.slip.at(7).path);
  TEST_EQUALITY(r.slip.at(7).net, h.slip.at(7).net);
  TEST_EQUALITY(r.slip.at(9).net, h.slip.at(9).net);
  TEST_EQUALITY(r.slip.at(11).path, 0.0);
  TEST_EQUALITY(r.bounds.size(), 2u);  // node 9 had none
  TEST_EQUALITY(r.bounds.at(7), h.bounds.at(7));
  TEST_EQUALITY(r.bounds.at(11), 0.0);
  // Tresca: no bounds at all.
  contact::FrictionHistory tresca;
  tresca.slip[3] = {1.0, -1.0};
  contact::writeFrictionRestart(dir, tresca);
  TEST_ASSERT(contact::readFrictionRestart(dir).bounds.empty());

  // A frictionless run's step has no friction file; a foreign or truncated file is refused.
  const std::string empty = dir + "/empty";
  std::filesystem::create_directories(empty);
  TEST_ASSERT(throwsNaming([&] { contact::readFrictionRestart(empty); },
                           empty + "/friction.txt: no friction state", out));
  {
    std::ofstream f(empty + "/friction.txt");
    f << "something else\n1\n";
  }
  TEST_ASSERT(throwsNaming([&] { contact::readFrictionRestart(empty); },
                           "not a tfeti_contact friction restart file", out));
  {
    std::ofstream f(empty + "/friction.txt");
    f << "tfeti_contact friction restart 1\n2\n7 -1 0.5 0.5\n";
  }
  TEST_ASSERT(throwsNaming([&] { contact::readFrictionRestart(empty); },
                           "truncated or malformed friction state", out));
  std::filesystem::remove_all(dir);
}

}  // namespace
