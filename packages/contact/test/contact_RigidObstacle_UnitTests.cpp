// Rigid obstacles (line and circle in 2D, plane and sphere in 3D, one implementation) against
// their closed forms: gap, normal, closest point and the row's coefficients; the row as the
// linearization of the exact gap (the ball's remainder lies in [0, |v|^2 / (2 |x - c|)]); the
// search radius; bad input named. And the ContactMaster interface: a mesh boundary as master
// (2D segments, 3D faces) and an obstacle give the same rows as the functions they wrap.
#include <Teuchos_UnitTestHarness.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "contact_ContactMaster.hpp"
#include "contact_RigidObstacle.hpp"

namespace {

using contact::ContactRowsResult;
using contact::ContactSearchOptions;
using contact::RigidObstacle;

const std::string kMeshDir = CONTACT_TEST_MESH_DIR;

ContactSearchOptions radius(double r) {
  ContactSearchOptions o;
  o.searchRadius = r;
  return o;
}

RigidObstacle halfSpace(int dim, std::array<double, 3> p, std::array<double, 3> n) {
  RigidObstacle b;
  b.dim = dim;
  b.shape = RigidObstacle::Shape::HalfSpace;
  b.point = p;
  b.normal = n;
  return b;
}

RigidObstacle ball(int dim, std::array<double, 3> c, double r) {
  RigidObstacle b;
  b.dim = dim;
  b.shape = RigidObstacle::Shape::Ball;
  b.point = c;
  b.radius = r;
  return b;
}

std::vector<double> randomPoints(int dim, int n, unsigned seed, double lo, double hi) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(lo, hi);
  std::vector<double> x(static_cast<std::size_t>(dim) * n);
  for (double& v : x) v = u(rng);
  return x;
}

TEUCHOS_UNIT_TEST(RigidObstacle, HalfSpaceClosedForm) {
  for (int dim : {2, 3}) {
    const std::array<double, 3> p{0.3, -0.2, dim == 3 ? 0.1 : 0.0};
    const std::array<double, 3> n{1.0, 2.0, dim == 3 ? -2.0 : 0.0};  // |n| = sqrt5 or 3
    const double len = dim == 3 ? 3.0 : std::sqrt(5.0);
    const RigidObstacle b = halfSpace(dim, p, n);
    const int count = 50;
    const std::vector<double> x = randomPoints(dim, count, 5 + dim, -1.0, 1.0);
    std::vector<int> slaves;
    for (int k = 0; k < count; ++k) slaves.push_back(k);
    const ContactRowsResult r = contact::computeObstacleRows(b, x, slaves, radius(0.6));
    int expected = 0;
    std::size_t j = 0;
    for (int k = 0; k < count; ++k) {
      double g = 0.0;
      for (int i = 0; i < dim; ++i) g += (x[dim * k + i] - p[i]) * n[i] / len;
      if (std::abs(g) > 0.6) continue;
      ++expected;
      TEST_ASSERT(j < r.rows.size());
      if (j >= r.rows.size()) break;
      const auto& row = r.rows[j++];
      TEST_EQUALITY(row.slaveNode, k);
      TEST_COMPARE(std::abs(row.gap - g), <, 1e-15);
      TEST_EQUALITY(row.entries.size(), std::size_t(dim));
      for (int i = 0; i < dim; ++i) {
        TEST_COMPARE(std::abs(row.normal[i] - n[i] / len), <, 1e-15);
        TEST_EQUALITY(row.entries[i].node, k);
        TEST_EQUALITY(row.entries[i].component, i);
        TEST_COMPARE(std::abs(row.entries[i].coef + n[i] / len), <, 1e-15);
      }
      // The closest point is on the plane and x - x_m = g n.
      double onPlane = 0.0;
      for (int i = 0; i < dim; ++i) {
        onPlane += (row.point[i] - p[i]) * n[i];
        TEST_COMPARE(std::abs(x[dim * k + i] - row.point[i] - g * n[i] / len), <, 1e-15);
      }
      TEST_COMPARE(std::abs(onPlane), <, 1e-15);
    }
    TEST_EQUALITY(static_cast<int>(r.rows.size()), expected);
    TEST_EQUALITY(r.beyondRadius, count - expected);
    TEST_COMPARE(expected, >, 10);
    TEST_EQUALITY(r.candidatePairs, static_cast<long long>(count));
  }
}

TEUCHOS_UNIT_TEST(RigidObstacle, BallClosedFormAndLinearization) {
  for (int dim : {2, 3}) {
    const std::array<double, 3> c{0.1, 1.2, dim == 3 ? -0.3 : 0.0};
    const double R = 0.8;
    const RigidObstacle b = ball(dim, c, R);
    const int count = 60;
    const std::vector<double> x = randomPoints(dim, count, 17 + dim, -1.0, 2.0);
    std::vector<int> slaves;
    for (int k = 0; k < count; ++k) slaves.push_back(k);
    const ContactRowsResult r = contact::computeObstacleRows(b, x, slaves, radius(10.0));
    TEST_EQUALITY(static_cast<int>(r.rows.size()), count);
    // A displacement v of every node: the rows on x + v against the linearization about x.
    const std::vector<double> v = randomPoints(dim, count, 99, -1e-2, 1e-2);
    const ContactRowsResult moved = contact::computeObstacleRows(b, x, slaves, radius(10.0), v);
    for (int k = 0; k < count; ++k) {
      const auto& row = r.rows[k];
      double dist = 0.0, v2 = 0.0, bv = 0.0;
      for (int i = 0; i < dim; ++i) {
        dist += (x[dim * k + i] - c[i]) * (x[dim * k + i] - c[i]);
        v2 += v[dim * k + i] * v[dim * k + i];
      }
      dist = std::sqrt(dist);
      TEST_COMPARE(std::abs(row.gap - (dist - R)), <, 1e-15);
      double onSphere = 0.0;
      for (int i = 0; i < dim; ++i) {
        TEST_COMPARE(std::abs(row.normal[i] - (x[dim * k + i] - c[i]) / dist), <, 1e-15);
        onSphere += (row.point[i] - c[i]) * (row.point[i] - c[i]);
      }
      TEST_COMPARE(std::abs(std::sqrt(onSphere) - R), <, 1e-15);
      for (const auto& e : row.entries) bv += e.coef * v[dim * e.node + e.component];
      // g(x + v) = g(x) + n . v + remainder, remainder in [0, |v|^2 / (2 |x - c|)].
      const double remainder = moved.rows[k].gap - (row.gap - bv);
      TEST_COMPARE(remainder, >=, -1e-15);
      TEST_COMPARE(remainder, <=, v2 / (2.0 * dist) + 1e-15);
    }
  }
}

template <class F>
std::string messageOf(F&& f) {
  try {
    f();
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

TEUCHOS_UNIT_TEST(RigidObstacle, BadInputIsNamed) {
  const std::vector<double> x{0.0, 0.0, 1.0, 1.0};
  auto rows = [&](const RigidObstacle& b) {
    contact::computeObstacleRows(b, x, {0, 1}, radius(1));
  };
  TEST_ASSERT(messageOf([&] {
                rows(halfSpace(2, {0, 0, 0}, {0, 0, 0}));
              }).find("normal is zero") != std::string::npos);
  TEST_ASSERT(messageOf([&] {
                rows(ball(2, {0, 0, 0}, -1.0));
              }).find("radius") != std::string::npos);
  TEST_ASSERT(messageOf([&] {
                rows(ball(2, {0, 0, 0}, 0.5));
              }).find("centre") != std::string::npos);  // node 0 at the centre
  TEST_ASSERT(messageOf([&] {
                rows(halfSpace(2, {0, 0, 1}, {0, 1, 0}));
              }).find("z component") != std::string::npos);
  TEST_ASSERT(messageOf([&] {
                rows(halfSpace(4, {0, 0, 0}, {0, 1, 0}));
              }).find("dimension") != std::string::npos);
  TEST_ASSERT(messageOf([&] {
                rows(halfSpace(2, {NAN, 0, 0}, {0, 1, 0}));
              }).find("point[0]") != std::string::npos);
  TEST_THROW(contact::computeObstacleRows(halfSpace(3, {0, 0, 0}, {0, 0, 1}), x, {0}, radius(1)),
             std::invalid_argument);  // 4 values are not x, y, z per node
  TEST_EQUALITY(static_cast<int>(contact::obstacleShapeFromName("circle", 2)),
                static_cast<int>(RigidObstacle::Shape::Ball));
  TEST_EQUALITY(static_cast<int>(contact::obstacleShapeFromName("plane", 3)),
                static_cast<int>(RigidObstacle::Shape::HalfSpace));
  const std::string wrong = messageOf([] { contact::obstacleShapeFromName("plane", 2); });
  TEST_ASSERT(wrong.find("\"line\"") != std::string::npos &&
              wrong.find("\"circle\"") != std::string::npos);
}

bool sameRows(const ContactRowsResult& a, const ContactRowsResult& b) {
  if (a.rows.size() != b.rows.size() || a.candidatePairs != b.candidatePairs) return false;
  for (std::size_t k = 0; k < a.rows.size(); ++k)
    if (a.rows[k].slaveNode != b.rows[k].slaveNode || a.rows[k].facet != b.rows[k].facet ||
        a.rows[k].gap != b.rows[k].gap || a.rows[k].entries.size() != b.rows[k].entries.size())
      return false;
  return true;
}

std::vector<int> nodesOf(const contact::GmshBoundary& g) {
  std::vector<int> v(g.edges.begin(), g.edges.end());
  std::sort(v.begin(), v.end());
  v.erase(std::unique(v.begin(), v.end()), v.end());
  return v;
}

// The height-function gap (Gap direction) against hand calculations: step-42's sphere (R = 0.6,
// centre (0.5, 0.5, 1.59)) above nodes of the top face z = 1, gaps measured vertically:
// g(x, y) = 1.59 - sqrt(R^2 - r^2) - z with r the horizontal distance to the axis, row u_z <= g;
// a node whose vertical misses the sphere gets no row; off the axis the vertical gap exceeds the
// closest-point one. A 2D line y = 1 + x/2 with gaps along +y from y = 0: g = 1 + x/2.
TEUCHOS_UNIT_TEST(RigidObstacle, HeightFunctionAgainstHandCalculation) {
  RigidObstacle s = ball(3, {0.5, 0.5, 1.59}, 0.6);
  s.gapDirection = {0.0, 0.0, 2.0};  // any length
  // Nodes on z = 1 at r = 0, 0.3 (along x), 0.5 (along the diagonal), 0.7 (misses: r > R).
  const double h = 0.5 / std::sqrt(2.0);
  const std::vector<double> x = {0.5,     0.5,     1.0, 0.8, 0.5, 1.0,
                                 0.5 + h, 0.5 + h, 1.0, 1.2, 0.5, 1.0};
  const ContactRowsResult r = contact::computeObstacleRows(s, x, {0, 1, 2, 3}, radius(1.0));
  TEST_EQUALITY(static_cast<int>(r.rows.size()), 3);
  TEST_EQUALITY(r.beyondRadius, 1LL);
  const double radii[3] = {0.0, 0.3, 0.5};
  for (int k = 0; k < 3; ++k) {
    const auto& row = r.rows[k];
    const double g = 1.59 - std::sqrt(0.36 - radii[k] * radii[k]) - 1.0;
    TEST_FLOATING_EQUALITY(row.gap, g, 1e-14);
    // Only u_z, coefficient +1: u_z <= g.
    TEST_EQUALITY(static_cast<int>(row.entries.size()), 3);
    for (const auto& e : row.entries)
      TEST_COMPARE(std::abs(e.coef - (e.component == 2 ? 1.0 : 0.0)), <, 1e-15);
    TEST_FLOATING_EQUALITY(row.point[2], 1.0 + g, 1e-14);
  }
  // Off the axis the vertical gap exceeds the closest-point one (the normal is tilted).
  const ContactRowsResult normal =
      contact::computeObstacleRows(ball(3, {0.5, 0.5, 1.59}, 0.6), x, {2}, radius(1.0));
  TEST_COMPARE(normal.rows[0].gap, <, r.rows[2].gap);

  // The line y = 1 + x/2 (outward normal along (1/2, -1)), nodes at y = 0.
  RigidObstacle line = halfSpace(2, {0.0, 1.0, 0.0}, {0.5, -1.0, 0.0});
  line.gapDirection = {0.0, 1.0, 0.0};
  const ContactRowsResult l =
      contact::computeObstacleRows(line, {0.0, 0.0, 1.0, 0.0, -2.0, 0.0}, {0, 1, 2}, radius(10));
  TEST_EQUALITY(static_cast<int>(l.rows.size()), 3);
  const double xs[3] = {0.0, 1.0, -2.0};
  for (int k = 0; k < 3; ++k) {
    TEST_COMPARE(std::abs(l.rows[k].gap - (1.0 + xs[k] / 2.0)), <, 1e-14);
    TEST_COMPARE(std::abs(l.rows[k].normal[1] + 1.0), <, 1e-15);
  }

  // A direction that points out of a half-space, and a 2D direction with a z component, are
  // errors naming the gap direction.
  RigidObstacle away = halfSpace(3, {0, 0, 1}, {0, 0, -1});
  away.gapDirection = {0, 0, -1};
  TEST_THROW(contact::computeObstacleRows(away, {0, 0, 0}, {0}, radius(1)), std::invalid_argument);
  RigidObstacle flat = ball(2, {0, 1, 0}, 0.5);
  flat.gapDirection = {0, 1, 1};
  TEST_THROW(contact::computeObstacleRows(flat, {0, 0}, {0}, radius(1)), std::invalid_argument);
}

// Small strain reads the height at the reference position: a displaced node's gap is the
// reference gap minus its displacement along d (the classical Signorini form); at the current
// position (heightAtReference false) the horizontal displacement moves it under another part of
// the sphere.
TEUCHOS_UNIT_TEST(RigidObstacle, HeightAtTheReferencePosition) {
  RigidObstacle s = ball(3, {0.5, 0.5, 1.59}, 0.6);
  s.gapDirection = {0.0, 0.0, 1.0};
  const std::vector<double> x = {0.8, 0.5, 1.0};
  const std::vector<double> u = {0.05, -0.02, 0.003};
  const double g0 = 1.59 - std::sqrt(0.36 - 0.3 * 0.3) - 1.0;
  s.heightAtReference = true;
  const ContactRowsResult ref = contact::computeObstacleRows(s, x, {0}, radius(1.0), u);
  TEST_EQUALITY(static_cast<int>(ref.rows.size()), 1);
  TEST_FLOATING_EQUALITY(ref.rows[0].gap, g0 - 0.003, 1e-13);
  s.heightAtReference = false;
  const ContactRowsResult cur = contact::computeObstacleRows(s, x, {0}, radius(1.0), u);
  const double r2 = 0.35 * 0.35 + 0.02 * 0.02;
  TEST_FLOATING_EQUALITY(cur.rows[0].gap, 1.59 - std::sqrt(0.36 - r2) - 1.003, 1e-13);
}

TEUCHOS_UNIT_TEST(ContactMaster, OneInterfaceForSegmentsFacesAndObstacles) {
  // 2D: the cylinder's nodes against the block's top.
  const contact::GmshMesh m2 = contact::loadMesh(kMeshDir + "/cylinder_on_block.geo");
  const auto master2 = contact::makeMeshContactMaster(m2, "block_contact", radius(0.3));
  TEST_EQUALITY(master2->dimension(), 2);
  contact::MasterSurface segs;
  const auto& bc = m2.boundary("block_contact");
  segs.nodesPerSegment = bc.nodesPerEdge;
  segs.segments = bc.edges;
  const auto& block = m2.body("block");
  contact::orientSegmentsByElements(segs, m2.coords, block.type, block.connectivity);
  const std::vector<int> slaves2 = nodesOf(m2.boundary("cylinder_contact"));
  const ContactRowsResult a2 = master2->rows(m2.coords, slaves2);
  TEST_ASSERT(sameRows(a2, contact::computeNodeToSegment(m2.coords, slaves2, segs, radius(0.3))));
  TEST_COMPARE(a2.rows.size(), >, 0u);
  TEST_ASSERT(master2->masterNodes() == nodesOf(bc));
  // 3D: the sphere's nodes against the block's top faces.
  const contact::GmshMesh m3 = contact::loadMesh(kMeshDir + "/sphere_on_block.geo");
  const auto master3 = contact::makeMeshContactMaster(m3, "block_contact", radius(0.3));
  TEST_EQUALITY(master3->dimension(), 3);
  const std::vector<int> slaves3 = nodesOf(m3.boundary("sphere_contact"));
  const ContactRowsResult a3 = master3->rows(m3.coords, slaves3);
  const contact::MasterFaceSurface faces =
      contact::masterFacesOfBoundary(m3, m3.boundary("block_contact"));
  TEST_ASSERT(sameRows(a3, contact::computeNodeToFace(m3.coords, slaves3, faces, radius(0.3))));
  TEST_COMPARE(a3.rows.size(), >, 0u);
  // The block's top as the plane z = 0 gives the same gaps for the nodes over it (the rows'
  // entries differ: the obstacle has none on the block).
  const auto plane = contact::makeObstacleMaster(halfSpace(3, {0, 0, 0}, {0, 0, 1}), radius(0.3));
  TEST_EQUALITY(plane->dimension(), 3);
  TEST_ASSERT(plane->masterNodes().empty());
  const ContactRowsResult p3 = plane->rows(m3.coords, slaves3);
  TEST_EQUALITY(p3.rows.size(), a3.rows.size());
  for (std::size_t k = 0; k < std::min(p3.rows.size(), a3.rows.size()); ++k) {
    TEST_EQUALITY(p3.rows[k].slaveNode, a3.rows[k].slaveNode);
    TEST_COMPARE(std::abs(p3.rows[k].gap - a3.rows[k].gap), <, 1e-14);
    TEST_EQUALITY(p3.rows[k].entries.size(), 3u);
  }
  TEST_THROW(contact::makeMeshContactMaster(m3, "no_such", radius(0.3)), std::invalid_argument);
  TEST_THROW(contact::makeObstacleMaster(ball(3, {0, 0, 0}, 0.0), radius(0.3)),
             std::invalid_argument);
}

}  // namespace
