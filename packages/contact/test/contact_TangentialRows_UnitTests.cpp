// Tangential contact rows (friction) against exact kinematics: on a straight master (linear and
// quadratic segments, rotated), a curved one (a circle of quadratic segments) and a rigid
// obstacle, each tangential row is orthogonal to its normal row, its tangent is the unit vector
// n turned counter-clockwise, and for any rigid motion u = c + omega x (x - x0) of slave and
// master together B_T u = -omega gap (the relative displacement omega x (gap n) is along t),
// while moving the slave node alone by a along t gives B_T u = -a (the slip of the slave). In
// 3D the two tangents and n form a right-handed orthonormal basis. Rows that do not list dim
// components per node are refused. Friction's rows leave out the directions in which the row's
// nodes are held (a symmetry plane through the contact): the rest is tangential, orthogonal to
// the held direction, and the row set is tangentialRows' where nothing is held. On a symmetry
// plane the tangent normal to it goes whatever a mortar row's master weights, also on a mesh
// through the problem's own friction rows.
#include <Teuchos_UnitTestHarness.hpp>
#include <Tpetra_Core.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <utility>
#include <vector>

#include "contact_ElasticContactProblem.hpp"
#include "contact_Friction.hpp"
#include "contact_NodeToSegment.hpp"
#include "contact_RigidObstacle.hpp"
#include "contact_TangentialRows.hpp"
#include "plasticity_ElasticLaw.hpp"

namespace {

using contact::ContactRow;
using contact::MasterSurface;
using contact::tangentialRows;

const double kPi = 3.14159265358979323846;

struct Setup {
  std::vector<double> coords;
  MasterSurface master;
  std::vector<int> slaves;
  int add(double x, double y) {
    coords.push_back(x);
    coords.push_back(y);
    return static_cast<int>(coords.size() / 2) - 1;
  }
};

// Rigid motion u = c + omega e_z x (x - x0) of every node.
std::vector<double> rigid(const std::vector<double>& coords, double cx, double cy, double omega) {
  std::vector<double> u(coords.size());
  for (std::size_t n = 0; n < coords.size() / 2; ++n) {
    u[2 * n] = cx - omega * (coords[2 * n + 1] - 0.3);
    u[2 * n + 1] = cy + omega * (coords[2 * n] + 0.2);
  }
  return u;
}

// Checks every row of a 2D master against the kinematic identities; returns the number of rows.
int checkRows(Teuchos::FancyOStream& out, bool& success, const Setup& s,
              const contact::ContactRowsResult& res) {
  const std::vector<double> u = rigid(s.coords, 0.7, -0.4, 0.05);
  for (const ContactRow& row : res.rows) {
    const std::vector<ContactRow> t = tangentialRows(row, 2);
    TEST_EQUALITY(t.size(), 1u);
    const ContactRow& tr = t[0];
    TEST_EQUALITY(tr.entries.size(), row.entries.size());
    double dot = 0.0, norm2 = 0.0;
    for (std::size_t k = 0; k < row.entries.size(); ++k) {
      TEST_EQUALITY(tr.entries[k].node, row.entries[k].node);
      TEST_EQUALITY(tr.entries[k].component, row.entries[k].component);
      dot += tr.entries[k].coef * row.entries[k].coef;
      norm2 += row.entries[k].coef * row.entries[k].coef;
    }
    // Each node contributes s^2 (t . n) = 0.
    TEST_COMPARE(std::abs(dot), <, 1e-14 * norm2);
    TEST_FLOATING_EQUALITY(tr.normal[0], -row.normal[1], 1e-15);
    TEST_FLOATING_EQUALITY(tr.normal[1], row.normal[0], 1e-15);
    TEST_EQUALITY(tr.gap, 0.0);
    // Slip of a rigid motion of everything: omega times the gap.
    const double slip = contact::applyRow(tr, 2, u);
    TEST_COMPARE(std::abs(slip + 0.05 * row.gap), <, 1e-14);
    // The slave alone moved along t by 1e-3 (and along n, which must not count).
    std::vector<double> us(s.coords.size(), 0.0);
    us[2 * row.slaveNode] = 1e-3 * tr.normal[0] + 2e-3 * row.normal[0];
    us[2 * row.slaveNode + 1] = 1e-3 * tr.normal[1] + 2e-3 * row.normal[1];
    TEST_COMPARE(std::abs(contact::applyRow(tr, 2, us) + 1e-3), <, 1e-17);
    TEST_COMPARE(std::abs(contact::applyRow(row, 2, us) + 2e-3), <, 1e-17);
  }
  return static_cast<int>(res.rows.size());
}

TEUCHOS_UNIT_TEST(TangentialRows, StraightMasterLinearAndQuadratic) {
  for (int nps : {2, 3}) {
    for (double theta : {0.0, 0.4, 2.0}) {
      Setup s;
      s.master.nodesPerSegment = nps;
      const int nseg = 8;
      for (int i = 0; i <= nseg; ++i) s.add(static_cast<double>(i) / nseg, 0.0);
      for (int i = nseg; i > 0; --i) {  // body below: walked from x = 1 to 0
        s.master.segments.push_back(i);
        s.master.segments.push_back(i - 1);
        if (nps == 3) s.master.segments.push_back(s.add((i - 0.5) / nseg, 0.0));
      }
      for (int k = 0; k < 9; ++k)
        s.slaves.push_back(s.add(0.05 + 0.11 * k, 0.01 * (k % 3) - 0.005));
      const double c = std::cos(theta), sn = std::sin(theta);
      for (std::size_t n = 0; n < s.coords.size() / 2; ++n) {
        const double x = s.coords[2 * n], y = s.coords[2 * n + 1];
        s.coords[2 * n] = c * x - sn * y;
        s.coords[2 * n + 1] = sn * x + c * y;
      }
      contact::NodeToSegmentOptions o;
      o.searchRadius = 0.1;
      const auto res = contact::computeNodeToSegment(s.coords, s.slaves, s.master, o);
      TEST_EQUALITY(checkRows(out, success, s, res), 9);
      // The tangent of the rotated x axis, walked from x = 1 to 0: -(cos, sin).
      for (const auto& row : res.rows) {
        const auto t = tangentialRows(row, 2)[0].normal;
        TEST_COMPARE(std::abs(t[0] + c) + std::abs(t[1] + sn), <, 1e-14);
      }
    }
  }
}

TEUCHOS_UNIT_TEST(TangentialRows, CurvedMasterQuadraticCircle) {
  Setup s;
  s.master.nodesPerSegment = 3;
  const int n = 24;
  for (int i = 0; i < n; ++i) s.add(std::cos(2 * kPi * i / n), std::sin(2 * kPi * i / n));
  for (int i = 0; i < n; ++i) {  // the disc is the body: counter-clockwise
    s.master.segments.push_back(i);
    s.master.segments.push_back((i + 1) % n);
    const double a = 2 * kPi * (i + 0.5) / n;
    s.master.segments.push_back(s.add(std::cos(a), std::sin(a)));
  }
  for (int k = 0; k < 40; ++k) {
    const double a = 0.1 + 2 * kPi * k / 40, r = 1.0 + 0.01 * ((k % 5) - 2);
    s.slaves.push_back(s.add(r * std::cos(a), r * std::sin(a)));
  }
  contact::NodeToSegmentOptions o;
  o.searchRadius = 0.1;
  const auto res = contact::computeNodeToSegment(s.coords, s.slaves, s.master, o);
  TEST_EQUALITY(checkRows(out, success, s, res), 40);
  // The tangent of the circle at the slave's angle, counter-clockwise (a to b), to the
  // parabola's accuracy.
  double worst = 0.0;
  for (const auto& row : res.rows) {
    const double x = s.coords[2 * row.slaveNode], y = s.coords[2 * row.slaveNode + 1];
    const double r = std::hypot(x, y);
    const auto t = tangentialRows(row, 2)[0].normal;
    worst = std::max(worst, std::abs(t[0] + y / r) + std::abs(t[1] - x / r));
  }
  out << "largest tangent error on the circle: " << worst << "\n";
  TEST_COMPARE(worst, <, 1e-3);
}

TEUCHOS_UNIT_TEST(TangentialRows, RigidObstacleAndThreeDimensionalBasis) {
  contact::RigidObstacle ball;
  ball.dim = 2;
  ball.shape = contact::RigidObstacle::Shape::Ball;
  ball.point = {0.0, -1.0, 0.0};
  ball.radius = 1.0;
  contact::ContactSearchOptions o;
  o.searchRadius = 0.2;
  Setup s;
  for (int k = 0; k < 5; ++k) s.slaves.push_back(s.add(-0.2 + 0.1 * k, 0.01));
  const auto res = contact::computeObstacleRows(ball, s.coords, s.slaves, o);
  TEST_EQUALITY(res.rows.size(), 5u);
  for (const auto& row : res.rows) {
    const auto tr = tangentialRows(row, 2)[0];
    TEST_EQUALITY(tr.entries.size(), 2u);
    std::vector<double> us(s.coords.size(), 0.0);
    us[2 * row.slaveNode] = 1e-3 * tr.normal[0];
    us[2 * row.slaveNode + 1] = 1e-3 * tr.normal[1];
    TEST_COMPARE(std::abs(contact::applyRow(tr, 2, us) + 1e-3), <, 1e-17);
    TEST_COMPARE(std::abs(contact::applyRow(row, 2, us)), <, 1e-17);
  }
  for (std::array<double, 3> n : {std::array<double, 3>{0.0, 0.0, 1.0},
                                  {1.0, 0.0, 0.0},
                                  {0.6, 0.0, -0.8},
                                  {0.48, 0.6, 0.64},
                                  {0.0, 0.0, -1.0}}) {
    const auto t = contact::tangentBasis(n, 3);
    TEST_EQUALITY(t.size(), 2u);
    auto dot = [](const std::array<double, 3>& a, const std::array<double, 3>& b) {
      return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    };
    TEST_FLOATING_EQUALITY(dot(t[0], t[0]), 1.0, 1e-14);
    TEST_FLOATING_EQUALITY(dot(t[1], t[1]), 1.0, 1e-14);
    TEST_COMPARE(std::abs(dot(t[0], t[1])) + std::abs(dot(t[0], n)) + std::abs(dot(t[1], n)), <,
                 1e-14);
    // Right-handed: t1 x t2 = n.
    const std::array<double, 3> c{t[0][1] * t[1][2] - t[0][2] * t[1][1],
                                  t[0][2] * t[1][0] - t[0][0] * t[1][2],
                                  t[0][0] * t[1][1] - t[0][1] * t[1][0]};
    TEST_COMPARE(std::abs(c[0] - n[0]) + std::abs(c[1] - n[1]) + std::abs(c[2] - n[2]), <, 1e-14);
  }
}

TEUCHOS_UNIT_TEST(TangentialRows, ThreeDimensionalFrameDoesNotFlip) {
  // Normals around +z and -z (a sphere on a block), among them |n_x| = |n_y|, where a frame
  // built on the axis least aligned with n switches axes: a change of n by rounding (1e-15)
  // moves the frame by rounding, and a small change of n moves it by about as much.
  auto unit = [](std::array<double, 3> v) {
    const double l = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    for (double& c : v) c /= l;
    return v;
  };
  double worst = 0.0, worstSmall = 0.0;
  for (double sz : {1.0, -1.0})
    for (int k = 0; k < 64; ++k) {
      const double phi = 0.25 * M_PI * k / 8.0, theta = 0.6 * (k % 9) / 8.0;
      const auto n = unit(
          {std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), sz * std::cos(theta)});
      for (const auto& [eps, slot] : {std::pair<double, double*>{1e-15, &worst},
                                      std::pair<double, double*>{1e-6, &worstSmall}}) {
        const auto m = unit({n[0] + eps, n[1] - eps, n[2]});
        const auto a = contact::tangentBasis(n, 3), b = contact::tangentBasis(m, 3);
        double d = 0.0;
        for (int j = 0; j < 2; ++j)
          for (int c = 0; c < 3; ++c) d = std::max(d, std::abs(a[j][c] - b[j][c]));
        *slot = std::max(*slot, d / eps);
      }
    }
  out << "frame change / normal change: rounding " << worst << ", 1e-6: " << worstSmall << "\n";
  TEST_COMPARE(worst, <, 100.0);
  TEST_COMPARE(worstSmall, <, 10.0);
}

// A 3D node-to-face row: slave node 0 above the face of master nodes 1, 2, 3 (weights w).
ContactRow faceRow(const std::array<double, 3>& n, const std::array<double, 3>& w) {
  ContactRow row;
  row.slaveNode = 0;
  row.normal = n;
  for (int node = 0; node < 4; ++node) {
    const double s = node == 0 ? -1.0 : w[static_cast<std::size_t>(node - 1)];
    for (int c = 0; c < 3; ++c)
      row.entries.push_back({node, c, s * n[static_cast<std::size_t>(c)]});
  }
  return row;
}

TEUCHOS_UNIT_TEST(TangentialRows, FrictionLeavesOutHeldDirections) {
  const double e = 1e-3;  // the deformed normal's tilt out of the symmetry plane
  const std::array<double, 3> n{0.1 / std::sqrt(1.01 + e * e), -e / std::sqrt(1.01 + e * e),
                                1.0 / std::sqrt(1.01 + e * e)};
  auto dot = [](const std::array<double, 3>& a, const std::array<double, 3>& b) {
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
  };
  // Nodes 0, 1, 2 on the symmetry plane y = 0 (u_y held), node 3 off it.
  const auto heldY = [](int node, int c) { return c == 1 && node != 3; };
  // The closest point on the held edge (node 3's weight 0), then tilted off it by 1e-5.
  for (double w3 : {0.0, 1e-5}) {
    const ContactRow row = faceRow(n, {0.4, 0.6 - w3, w3});
    const auto t = contact::frictionTangentialRows(row, 3, heldY);
    TEST_EQUALITY(t.size(), 1u);
    if (t.size() != 1u) continue;
    TEST_FLOATING_EQUALITY(dot(t[0].normal, t[0].normal), 1.0, 1e-14);
    TEST_COMPARE(std::abs(dot(t[0].normal, n)), <, 1e-15);
    TEST_EQUALITY(t[0].normal[1], 0.0);  // no y: independent of the symmetry rows
    // The row is the tangent applied to the same nodes: sliding the slave along it by a.
    std::vector<double> u(12, 0.0);
    for (int c = 0; c < 3; ++c) u[static_cast<std::size_t>(c)] = 1e-3 * t[0].normal[c];
    TEST_COMPARE(std::abs(contact::applyRow(t[0], 3, u) + 1e-3), <, 1e-17);
  }
  // A master point well inside the face (node 3 free, 30 % of the weight): both tangents.
  {
    const ContactRow row = faceRow(n, {0.3, 0.4, 0.3});
    const auto t = contact::frictionTangentialRows(row, 3, heldY);
    const auto plain = tangentialRows(row, 3);
    TEST_EQUALITY(t.size(), 2u);
    for (std::size_t j = 0; j < std::min(t.size(), plain.size()); ++j)
      for (std::size_t k = 0; k < plain[j].entries.size(); ++k)
        TEST_EQUALITY(t[j].entries[k].coef, plain[j].entries[k].coef);
  }
  // The slave not held: friction holds the master along y, both tangents stay.
  TEST_EQUALITY(contact::frictionTangentialRows(faceRow(n, {0.4, 0.6, 0.0}), 3,
                                                [](int node, int c) { return c == 1 && node > 0; })
                    .size(),
                2u);
  // Nothing held: tangentialRows'.
  TEST_EQUALITY(contact::frictionTangentialRows(faceRow(n, {0.4, 0.6, 0.0}), 3,
                                                [](int, int) { return false; })
                    .size(),
                2u);
  // Held in x and y (the axis of a quarter model), or everywhere: no tangential row. Held in
  // z only (along n): no tangent is held, both stay.
  TEST_EQUALITY(contact::frictionTangentialRows(faceRow(n, {0.4, 0.6, 0.0}), 3,
                                                [](int node, int c) { return c < 2 && node != 3; })
                    .size(),
                0u);
  TEST_EQUALITY(contact::frictionTangentialRows(faceRow(n, {0.4, 0.6, 0.0}), 3,
                                                [](int node, int c) { return c == 2 && node != 3; })
                    .size(),
                2u);
  // 2D: a slave and master held along the tangent x (a symmetry axis x = 0 through a contact
  // along y): no tangential row; held along y (the normal): the tangent stays.
  ContactRow row2;
  row2.slaveNode = 0;
  row2.normal = {0.0, 1.0, 0.0};
  row2.entries = {{0, 0, 0.0}, {0, 1, -1.0}, {1, 0, 0.0}, {1, 1, 1.0}, {2, 0, 0.0}, {2, 1, 0.0}};
  TEST_EQUALITY(
      contact::frictionTangentialRows(row2, 2, [](int node, int c) { return c == 0 && node < 2; })
          .size(),
      0u);
  TEST_EQUALITY(
      contact::frictionTangentialRows(row2, 2, [](int node, int c) { return c == 1 && node < 2; })
          .size(),
      1u);
}

// A dual mortar row of a slave node on the symmetry plane y = 0 (the 0.1M Cattaneo sphere's,
// rounded): the master's weight on the plane nodes 1, 2 and, with both signs, 5.6 % of the row's
// weight on the off-plane nodes 3 to 6. The 5 % rule keeps both tangents, and the one along y
// is then within 5 % of the symmetry rows' span. With the symmetry plane named (mirrored) the
// tangent along y goes whatever the master's weights; a slave node held in y by a Fixed or
// Prescribed boundary (held, not mirrored) keeps the rule.
TEUCHOS_UNIT_TEST(TangentialRows, SymmetryPlaneLeavesOutItsNormalWhateverTheMortarWeights) {
  const std::array<double, 3> n{0.0089, -0.0004, 1.0};
  const double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  const std::array<double, 3> unitN{n[0] / len, n[1] / len, n[2] / len};
  const std::vector<double> w{-1.0, 0.955, 0.008, -0.028, 0.021, 0.056, -0.0062};
  ContactRow row;
  row.slaveNode = 0;
  row.normal = unitN;
  for (int node = 0; node < static_cast<int>(w.size()); ++node)
    for (int c = 0; c < 3; ++c)
      row.entries.push_back(
          {node, c, w[static_cast<std::size_t>(node)] * unitN[static_cast<std::size_t>(c)]});
  const auto onPlane = [](int node, int c) { return c == 1 && node <= 2; };
  TEST_EQUALITY(contact::frictionTangentialRows(row, 3, onPlane).size(), 2u);
  const auto t = contact::frictionTangentialRows(row, 3, onPlane, onPlane);
  TEST_EQUALITY(t.size(), 1u);
  if (t.size() == 1u) TEST_COMPARE(std::abs(t[0].normal[1]), <, 1e-15);
  // Mirrored elsewhere only (another node, another component): the rule as before.
  TEST_EQUALITY(contact::frictionTangentialRows(row, 3, onPlane,
                                                [](int node, int c) { return c == 1 && node == 1; })
                    .size(),
                2u);
  TEST_EQUALITY(contact::frictionTangentialRows(row, 3, onPlane,
                                                [](int node, int c) { return c == 0 && node == 0; })
                    .size(),
                2u);
}

// The same on a mesh, through the problem's own friction rows: the Cattaneo sphere's half model
// (examples/cattaneo_sphere.geo, 2x coarser, dual mortar rows, the plane y = 0 a Symmetry
// boundary of both bodies). Some slave nodes on the plane have mortar rows that the 5 % rule
// alone keeps both tangents of (the case above; asserted, so the mesh does test it); frictionRows
// gives one row for each of them, two for the nodes off the plane.
TEUCHOS_UNIT_TEST(TangentialRows, FrictionRowsOfAMortarHalfModel) {
  contact::ElasticContactSpec spec;
  spec.meshFile = CONTACT_TEST_EXAMPLES_DIR "/cattaneo_sphere.geo";
  spec.meshOptions.sizeFactor = 2.0;
  const plasticity::ElasticLaw law(2.0e11, 0.3);
  spec.bodies = {{"sphere", 1, law}, {"block", 1, law}};
  spec.fixed = {"block_bottom"};
  spec.symmetry = {{"symmetry_y", 1}};
  spec.tractions = {{"sphere_top", {0.0, 0.0, -1.2732395e6}}};
  contact::ContactPairSpec pair;
  pair.where = "Contact problem";
  pair.slave = "sphere_contact";
  pair.master = "block_contact";
  pair.discretization = "mortar";
  pair.searchRadius = 0.1;
  spec.pairs = {pair};
  const auto comm = Tpetra::getDefaultComm();
  const contact::ElasticContactProblem p = contact::buildElasticContactProblem(spec, *comm);
  const auto held = [&](int node, int c) { return p.heldComponents.count({node, c}) > 0; };
  const auto mirrored = [&](int node, int c) { return p.mirroredComponents.count({node, c}) > 0; };
  std::size_t expected = 0, byTheWeightsAlone = 0, planeNodes = 0;
  for (const auto& row : p.contact.rows) {
    const auto rows = contact::frictionTangentialRows(row, 3, held, mirrored);
    expected += rows.size();
    if (!mirrored(row.slaveNode, 1)) continue;
    ++planeNodes;
    TEST_EQUALITY(rows.size(), 1u);
    if (contact::frictionTangentialRows(row, 3, held).size() == 2u) ++byTheWeightsAlone;
  }
  out << p.contact.rows.size() << " contact rows, " << planeNodes << " on the plane, "
      << byTheWeightsAlone << " of them with both tangents by the 5 % rule alone\n";
  TEST_COMPARE(planeNodes, >, 0u);
  TEST_COMPARE(byTheWeightsAlone, >, 0u);
  contact::ModelFriction friction;
  contact::FrictionSpec tresca;
  tresca.law = contact::FrictionSpec::Law::Tresca;
  tresca.slipBound = 1.0e6;
  friction.pairs = {tresca};
  TEST_EQUALITY(contact::frictionRows(p, friction, {}, {}, {}, 0).size(), expected);
}

TEUCHOS_UNIT_TEST(TangentialRows, RowsWithoutAllComponentsRefused) {
  ContactRow row;
  row.slaveNode = 7;
  row.normal = {0.0, 1.0, 0.0};
  row.entries = {{7, 1, -1.0}};  // the x component dropped
  TEST_THROW(tangentialRows(row, 2), std::invalid_argument);
  row.entries = {{7, 0, 0.0}, {7, 1, -1.0}, {3, 0, 0.0}};
  TEST_THROW(tangentialRows(row, 2), std::invalid_argument);
  row.entries = {{7, 0, 0.0}, {7, 1, -1.0}};
  TEST_THROW(contact::applyRow(row, 2, {0.0, 0.0}), std::invalid_argument);
  TEST_THROW(contact::tangentBasis(row.normal, 4), std::invalid_argument);
}

}  // namespace
