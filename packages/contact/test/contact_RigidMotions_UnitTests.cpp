// What holds the bodies (contact_RigidMotions.hpp) on the 2D contact patch (two blocks stacked on
// y = 0.5, tests/meshes/patch_blocks_2d.geo: "lower" (0, 1) x (0, 0.5), "upper" (0, 1) x (0.5, 1),
// the upper one's bottom the slave against the lower one's top): the free motions found and how
// they read, for supports that hold everything, nothing along x, and only a line of u_y.
#include <Teuchos_UnitTestHarness.hpp>
#include <Tpetra_Core.hpp>

#include <string>
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

}  // namespace
