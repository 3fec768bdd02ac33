// What holds the bodies (contact_RigidMotions.hpp) on the 2D contact patch (two blocks stacked on
// y = 0.5, tests/meshes/patch_blocks_2d.geo: "lower" (0, 1) x (0, 0.5), "upper" (0, 1) x (0.5, 1),
// the upper one's bottom the slave against the lower one's top): the free motions found and how
// they read, for supports that hold everything, nothing along x, and only a line of u_y.
#include <Teuchos_CommHelpers.hpp>
#include <Teuchos_UnitTestHarness.hpp>
#include <Tpetra_Core.hpp>

#include <limits>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "contact_ElasticContactProblem.hpp"
#include "contact_RigidMotions.hpp"

namespace {

contact::ElasticContactSpec patchSpec() {
  contact::ElasticContactSpec spec;
  spec.meshFile = CONTACT_TEST_MESH_DIR "/patch_blocks_2d.geo";
  const plasticity::ElasticLaw law(1.0e9, 0.3);
  spec.bodies = {{"lower", 1, law}, {"upper", 2, law}};
  spec.tractions = {{"upper_top", {0.0, -1.0e7}}};
  contact::ContactPairSpec pair;
  pair.where = "Contact problem";
  pair.slave = "upper_bottom";
  pair.master = "lower_top";
  pair.searchRadius = 0.01;
  spec.pairs = {pair};
  return spec;
}

std::vector<std::string> freeMotions(const contact::ElasticContactSpec& spec) {
  const auto comm = Tpetra::getDefaultComm();
  const contact::ElasticContactProblem p = contact::buildElasticContactProblem(spec, *comm);
  return contact::freeRigidMotions(spec, p, p.inequalities, *comm);
}

// The patch test's supports (the lower block's bottom fixed, both left edges u_x = 0): nothing
// free, and the check passes on every rank.
TEUCHOS_UNIT_TEST(RigidMotions, HeldPatchHasNoFreeMotion) {
  contact::ElasticContactSpec spec = patchSpec();
  spec.fixed = {"lower_bottom"};
  spec.symmetry = {{"upper_left", 0}};
  TEST_EQUALITY(freeMotions(spec).size(), 0u);
  const auto comm = Tpetra::getDefaultComm();
  const contact::ElasticContactProblem p = contact::buildElasticContactProblem(spec, *comm);
  TEST_NOTHROW(contact::requireRigidMotionsHeld(spec, p, p.inequalities, *comm));
}

// Without the upper block's u_x = 0 the contact rows (normal y) hold it along y and against
// rotating only: its translation along x is free, whichever subdomain of it (two) is asked.
TEUCHOS_UNIT_TEST(RigidMotions, ContactRowsHoldOnlyAlongTheirNormal) {
  contact::ElasticContactSpec spec = patchSpec();
  spec.fixed = {"lower_bottom"};
  const std::vector<std::string> free = freeMotions(spec);
  TEST_EQUALITY(free.size(), 1u);
  if (free.size() == 1u) TEST_EQUALITY(free[0], "body \"upper\": translation along x");
  const auto comm = Tpetra::getDefaultComm();
  const contact::ElasticContactProblem p = contact::buildElasticContactProblem(spec, *comm);
  TEST_THROW(contact::requireRigidMotionsHeld(spec, p, p.inequalities, *comm),
             std::invalid_argument);
}

// u_y = 0 on the lower block's left edge (x = 0) alone: both blocks slide along x, and they turn
// together about points of that edge. Three free motions in reduced row echelon form: each
// block's translation along x, and the turn, which reads as each block's rotation about a point
// of x = 0 (the two points differ by a translation along x, which the first two motions hold).
TEUCHOS_UNIT_TEST(RigidMotions, RotationsNameTheirCentre) {
  contact::ElasticContactSpec spec = patchSpec();
  spec.symmetry = {{"lower_left", 1}};
  const std::vector<std::string> free = freeMotions(spec);
  for (const auto& f : free) out << f << "\n";
  TEST_EQUALITY(free.size(), 3u);
  if (free.size() != 3u) return;
  TEST_EQUALITY(free[0], "body \"lower\": translation along x");
  TEST_EQUALITY(free[2], "body \"upper\": translation along x");
  TEST_EQUALITY(free[1],
                "body \"lower\": rotation about (0, 0.25), with body \"upper\": rotation about "
                "(0, 0.75)");
}

// The load limit (frictionLoadLimit) with the upper block held along x and against turning by
// u_x = 0 on its left edge: only its translation along y is free, and the contact rows push
// against it one way. Pressed down, they hold it at every load factor (no limit); pulled up,
// at none: the limit is 0 along that translation, every contact row lifted, and
// requireLoadHeld names it. The same on every rank (rank 0 holds the rows).
TEUCHOS_UNIT_TEST(RigidMotions, ContactRowsPushOnly) {
  const auto comm = Tpetra::getDefaultComm();
  contact::ElasticContactSpec spec = patchSpec();
  spec.fixed = {"lower_bottom"};
  spec.symmetry = {{"upper_left", 0}};
  {
    const contact::ElasticContactProblem p = contact::buildElasticContactProblem(spec, *comm);
    const auto limit = contact::frictionLoadLimit(spec, p, p.inequalities, {}, *comm);
    TEST_ASSERT(!limit.has_value());
    TEST_NOTHROW(contact::requireLoadHeld(limit));
  }
  spec.tractions = {{"upper_top", {0.0, 1.0e7}}};
  const contact::ElasticContactProblem p = contact::buildElasticContactProblem(spec, *comm);
  const auto limit = contact::frictionLoadLimit(spec, p, p.inequalities, {}, *comm);
  TEST_ASSERT(limit.has_value());
  if (!limit) return;
  TEST_EQUALITY(limit->motion, "body \"upper\": translation along y");
  TEST_EQUALITY(limit->loadFactor, 0.0);
  TEST_FLOATING_EQUALITY(limit->load, 1.0e7, 1e-12);  // the traction times the top's length 1
  int contactRows = static_cast<int>(p.inequalities.size());
  Teuchos::broadcast(*comm, 0, &contactRows);
  TEST_EQUALITY(limit->liftedRows, contactRows);
  TEST_COMPARE(limit->liftedRows, >, 0);
  TEST_THROW(contact::requireLoadHeld(limit), std::invalid_argument);
  try {
    contact::requireLoadHeld(limit);
  } catch (const std::invalid_argument& e) {
    const std::string what = e.what();
    out << what << "\n";
    TEST_ASSERT(what.find("nothing holds body \"upper\": translation along y against the load") !=
                std::string::npos);
  }
}

// Friction rows with fixed bounds on the free motions (rows made here: u_x of the upper block's
// bottom nodes, each with the bound 1e5, beside the contact rows), the upper block free to
// slide, lift and turn. Pushed along x by 3e5 and down by 1e6 on its top, it slides at the load
// factor (bounds' sum) / 3e5; pushed along x harder than down, it tips over its lower right
// corner at any load factor (the contact rows lift off, the friction rows do nothing along it).
TEUCHOS_UNIT_TEST(RigidMotions, SlidingAndTipping) {
  const auto comm = Tpetra::getDefaultComm();
  contact::ElasticContactSpec spec = patchSpec();
  spec.fixed = {"lower_bottom"};
  const auto limitFor = [&](double fx, double fy) {
    spec.tractions = {{"upper_top", {fx, fy}}};
    const contact::ElasticContactProblem p = contact::buildElasticContactProblem(spec, *comm);
    std::vector<tfeti::InequalityRow> rows = p.inequalities;
    double bounds = 0.0;
    for (const tfeti::InequalityRow& contactRow : p.inequalities) {
      tfeti::InequalityRow row;
      for (const auto& e : contactRow.entries)  // the slave node's u_y entry: its u_x instead
        if (p.bodyOfSubdomain[e.subdomain] == 1 && e.dof % 2 == 1) {
          row.entries.push_back({e.subdomain, e.dof - 1, 1.0});
          break;
        }
      row.lowerBound = -1.0e5;
      row.upperBound = 1.0e5;
      rows.push_back(row);
      bounds += 1.0e5;
    }
    Teuchos::broadcast(*comm, 0, &bounds);
    return std::make_pair(contact::frictionLoadLimit(spec, p, rows, {}, *comm), bounds);
  };
  const auto [sliding, bounds] = limitFor(3.0e5, -1.0e6);
  TEST_ASSERT(sliding.has_value());
  if (sliding) {
    out << sliding->motion << ": " << sliding->loadFactor << "\n";
    TEST_EQUALITY(sliding->motion, "body \"upper\": translation along x");
    TEST_FLOATING_EQUALITY(sliding->loadFactor, bounds / 3.0e5, 1e-12);
    TEST_EQUALITY(sliding->liftedRows, 0);
  }
  const auto tipping = limitFor(2.0e6, -1.0e6).first;
  TEST_ASSERT(tipping.has_value());
  if (tipping) {
    out << tipping->motion << ": " << tipping->loadFactor << "\n";
    TEST_EQUALITY(tipping->motion, "body \"upper\": rotation about (1, 0.5)");
    TEST_COMPARE(tipping->loadFactor, <=, 1e-12);
    TEST_COMPARE(tipping->liftedRows, >, 0);
  }
}

// Coulomb's cones on the same rows (each u_x row tied to its contact row, exact in 2D): pushed
// along x by 0.3 of the normal load, mu = 0.5 holds it at every load factor (no limit) and
// mu = 0.2 at none (0: the translation that slides and lifts by mu times the slip, every
// contact row lifted, (1, 0.2) / |(1, 0.2)|).
TEUCHOS_UNIT_TEST(RigidMotions, CoulombCones) {
  const auto comm = Tpetra::getDefaultComm();
  contact::ElasticContactSpec spec = patchSpec();
  spec.fixed = {"lower_bottom"};
  spec.tractions = {{"upper_top", {3.0e5, -1.0e6}}};
  const contact::ElasticContactProblem p = contact::buildElasticContactProblem(spec, *comm);
  const auto limitFor = [&](double mu) {
    std::vector<tfeti::InequalityRow> rows = p.inequalities;
    std::vector<contact::FrictionCone> cones;
    for (std::size_t i = 0; i < p.inequalities.size(); ++i) {
      tfeti::InequalityRow row;
      for (const auto& e : p.inequalities[i].entries)
        if (p.bodyOfSubdomain[e.subdomain] == 1 && e.dof % 2 == 1) {
          row.entries.push_back({e.subdomain, e.dof - 1, 1.0});
          break;
        }
      row.lowerBound = -std::numeric_limits<double>::infinity();
      row.upperBound = std::numeric_limits<double>::infinity();
      cones.push_back({static_cast<int>(i), {static_cast<int>(rows.size())}, mu});
      rows.push_back(row);
    }
    return contact::frictionLoadLimit(spec, p, rows, cones, *comm);
  };
  TEST_ASSERT(!limitFor(0.5).has_value());
  const auto sliding = limitFor(0.2);
  TEST_ASSERT(sliding.has_value());
  if (!sliding) return;
  out << sliding->motion << ": " << sliding->loadFactor << "\n";
  TEST_COMPARE(sliding->loadFactor, <=, 1e-12);
  TEST_EQUALITY(sliding->motion, "body \"upper\": translation along (0.9806, 0.1961)");
  int contactRows = static_cast<int>(p.inequalities.size());
  Teuchos::broadcast(*comm, 0, &contactRows);
  TEST_EQUALITY(sliding->liftedRows, contactRows);
  TEST_THROW(contact::requireLoadHeld(sliding), std::invalid_argument);
}

}  // namespace
