// Node-to-segment contact rows against exactly known geometry: flat surfaces (gaps, normals,
// coefficients, invariance under rigid motions), a circle meshed by 2- and 3-node segments
// (gap error and its convergence order, exact at the master nodes), corners, the search radius,
// free ends under both policies, the bucket search against the all-pairs one on a 2000-node
// case, orientation errors and their correction, and invalid input.
#include <Teuchos_UnitTestHarness.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <utility>
#include <vector>

#include "contact_NodeToSegment.hpp"

namespace {

using contact::computeNodeToSegment;
using contact::EndPolicy;
using contact::MasterSurface;
using contact::NodeToSegmentOptions;
using contact::NodeToSegmentResult;
using contact::NodeToSegmentRow;
using contact::ProjectionKind;

const double kPi = 3.14159265358979323846;

// Coordinates plus the surfaces built on them.
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

NodeToSegmentOptions radius(double r, EndPolicy policy = EndPolicy::Drop) {
  NodeToSegmentOptions o;
  o.searchRadius = r;
  o.endPolicy = policy;
  return o;
}

// B u for one row.
double applyRow(const NodeToSegmentRow& row, const std::vector<double>& u) {
  double s = 0.0;
  for (const auto& e : row.entries) s += e.coef * u[2 * e.node + e.component];
  return s;
}

// The displacement of the rigid motion  u = c + omega x (x - x0)  (plane, omega about z).
std::vector<double> rigid(const std::vector<double>& coords, double cx, double cy, double omega,
                          double x0, double y0) {
  std::vector<double> u(coords.size());
  for (std::size_t n = 0; n < coords.size() / 2; ++n) {
    u[2 * n] = cx - omega * (coords[2 * n + 1] - y0);
    u[2 * n + 1] = cy + omega * (coords[2 * n] - x0);
  }
  return u;
}

// A straight master on the x axis from 0 to 1 (nseg segments, body below, so it is walked from
// x = 1 to x = 0), rotated by theta about the origin together with everything added later.
Setup flatMaster(int nseg, int nodesPerSegment) {
  Setup s;
  s.master.nodesPerSegment = nodesPerSegment;
  for (int i = 0; i <= nseg; ++i) s.add(static_cast<double>(i) / nseg, 0.0);
  for (int i = nseg; i > 0; --i) {
    s.master.segments.push_back(i);
    s.master.segments.push_back(i - 1);
    if (nodesPerSegment == 3) s.master.segments.push_back(s.add((i - 0.5) / nseg, 0.0));
  }
  return s;
}

void rotate(std::vector<double>& coords, double theta) {
  const double c = std::cos(theta), s = std::sin(theta);
  for (std::size_t n = 0; n < coords.size() / 2; ++n) {
    const double x = coords[2 * n], y = coords[2 * n + 1];
    coords[2 * n] = c * x - s * y;
    coords[2 * n + 1] = s * x + c * y;
  }
}

// The circle of radius R about the origin (the disc is the body, so counter-clockwise), n
// segments; second order adds the midside nodes on the circle. Nodes 0..n-1 are the ends.
Setup circleMaster(int n, int nodesPerSegment, double R) {
  Setup s;
  s.master.nodesPerSegment = nodesPerSegment;
  for (int i = 0; i < n; ++i) s.add(R * std::cos(2 * kPi * i / n), R * std::sin(2 * kPi * i / n));
  for (int i = 0; i < n; ++i) {
    s.master.segments.push_back(i);
    s.master.segments.push_back((i + 1) % n);
    if (nodesPerSegment == 3) {
      const double a = 2 * kPi * (i + 0.5) / n;
      s.master.segments.push_back(s.add(R * std::cos(a), R * std::sin(a)));
    }
  }
  return s;
}

// A triangle fan of the disc for the circle above: element (centre, i, i+1[, midsides]).
std::vector<int> circleFan(Setup& s, int n, bool clockwise) {
  const int centre = s.add(0.0, 0.0);
  std::vector<int> conn;
  for (int i = 0; i < n; ++i) {
    int a = i, b = (i + 1) % n;
    if (clockwise) std::swap(a, b);
    conn.insert(conn.end(), {centre, a, b});
    if (s.master.nodesPerSegment == 3) {
      // Midside node positions do not matter to the orientation; only the ids are checked.
      const int m1 = s.add(0.5 * s.coords[2 * a], 0.5 * s.coords[2 * a + 1]);
      const int m3 = s.add(0.5 * s.coords[2 * b], 0.5 * s.coords[2 * b + 1]);
      conn.insert(conn.end(), {m1, s.master.segments[3 * i + 2], m3});
    }
  }
  return conn;
}

struct CircleErrors {
  double gap = 0.0;       // max |g - d|
  double normal = 0.0;    // max angle between n and the radial direction
  double atNodes = 0.0;   // max |g - d| for slave nodes on the rays of the master's end nodes
  double rotation = 0.0;  // max |B u| for a rigid rotation about (0.3, -0.2)
  int rows = 0, corners = 0;
};

CircleErrors circleErrors(int n, int nodesPerSegment) {
  const double R = 1.0, d = 0.05;
  Setup s = circleMaster(n, nodesPerSegment, R);
  const int m = 997;  // not a multiple of n: slave nodes fall all over the segments
  for (int k = 0; k < m; ++k) {
    const double a = 2 * kPi * (k + 0.37) / m;
    s.slaves.push_back(s.add((R + d) * std::cos(a), (R + d) * std::sin(a)));
  }
  std::vector<int> onRays;
  for (int i = 0; i < n; ++i) {
    const double a = 2 * kPi * i / n;
    onRays.push_back(s.add((R + d) * std::cos(a), (R + d) * std::sin(a)));
  }
  CircleErrors e;
  const std::vector<double> u = rigid(s.coords, 0.0, 0.0, 1.0, 0.3, -0.2);
  const NodeToSegmentResult r = computeNodeToSegment(s.coords, s.slaves, s.master, radius(0.2));
  for (const auto& row : r.rows) {
    const double x = s.coords[2 * row.slaveNode], y = s.coords[2 * row.slaveNode + 1];
    const double cosAngle = (row.normal[0] * x + row.normal[1] * y) / std::hypot(x, y);
    e.gap = std::max(e.gap, std::abs(row.gap - d));
    e.normal = std::max(e.normal, std::acos(std::min(1.0, cosAngle)));
    e.rotation = std::max(e.rotation, std::abs(applyRow(row, u)));
  }
  e.rows = static_cast<int>(r.rows.size());
  const NodeToSegmentResult rr = computeNodeToSegment(s.coords, onRays, s.master, radius(0.2));
  for (const auto& row : rr.rows) {
    e.atNodes = std::max(e.atNodes, std::abs(row.gap - d));
    e.corners += row.kind == ProjectionKind::Corner;
  }
  if (static_cast<int>(rr.rows.size()) != n) e.atNodes = 1e300;
  return e;
}

TEUCHOS_UNIT_TEST(NodeToSegment, FlatSurfacesGapsNormalsCoefficients) {
  const double d = 0.05;
  for (int nps : {2, 3})
    for (double theta : {0.0, 0.4, -2.5}) {
      out << "nodesPerSegment " << nps << ", rotation " << theta << "\n";
      Setup s = flatMaster(10, nps);
      const std::vector<double> xs{0.03, 0.23, 0.52, 0.77, 0.95};
      for (double x : xs) s.slaves.push_back(s.add(x, d));
      rotate(s.coords, theta);
      const NodeToSegmentResult r = computeNodeToSegment(s.coords, s.slaves, s.master, radius(0.2));
      TEST_EQUALITY(r.rows.size(), xs.size());
      TEST_EQUALITY(r.beyondRadius + r.beyondEnd, 0);
      if (r.rows.size() != xs.size()) continue;
      const double nx = -std::sin(theta), ny = std::cos(theta);
      for (std::size_t k = 0; k < xs.size(); ++k) {
        const NodeToSegmentRow& row = r.rows[k];
        TEST_EQUALITY(row.slaveNode, s.slaves[k]);
        TEST_FLOATING_EQUALITY(row.gap, d, 1e-12);
        TEST_COMPARE(std::abs(row.normal[0] - nx), <, 1e-14);
        TEST_COMPARE(std::abs(row.normal[1] - ny), <, 1e-14);
        TEST_EQUALITY(static_cast<int>(row.entries.size()), 2 + 2 * nps);
        // Segment i runs from node 10-i at x = (10-i)/10 to node 9-i: xi follows.
        const int seg = 9 - static_cast<int>(std::floor(xs[k] * 10));
        TEST_EQUALITY(row.facet, seg);
        const double xa = (10 - seg) / 10.0;
        TEST_COMPARE(std::abs(row.xi[0] - (-1.0 + 20.0 * (xa - xs[k]))), <, 1e-12);
        TEST_EQUALITY(static_cast<int>(row.kind), static_cast<int>(ProjectionKind::Interior));
        // Slave entries are -n; the master weights are the shape functions (>= 0 on a straight
        // segment for linear) summing to 1, so every component's coefficients sum to 0.
        TEST_COMPARE(std::abs(row.entries[0].coef + nx), <, 1e-15);
        TEST_COMPARE(std::abs(row.entries[1].coef + ny), <, 1e-15);
        double sum[2] = {0.0, 0.0}, weightSum = 0.0, xm = 0.0;
        for (std::size_t j = 0; j < row.entries.size(); ++j) {
          const auto& e = row.entries[j];
          sum[e.component] += e.coef;
          if (j >= 2 && e.component == 1) {
            weightSum += e.coef / ny;
            xm += e.coef / ny * s.coords[2 * e.node];
          }
        }
        TEST_COMPARE(std::abs(sum[0]), <, 1e-14);
        TEST_COMPARE(std::abs(sum[1]), <, 1e-14);
        TEST_COMPARE(std::abs(weightSum - 1.0), <, 1e-14);
        // The weights interpolate the closest point.
        TEST_COMPARE(std::abs(xm - row.point[0]), <, 1e-14);
        // Rigid translations and rotations (about any point) leave B u = 0.
        for (const auto& [cx, cy, om, x0, y0] :
             std::vector<std::array<double, 5>>{{0.3, -0.7, 0.0, 0.0, 0.0},
                                                {0.0, 0.0, 1.0, 0.3, -2.0},
                                                {0.1, 0.2, -0.8, 5.0, 7.0}})
          TEST_COMPARE(std::abs(applyRow(row, rigid(s.coords, cx, cy, om, x0, y0))), <, 1e-13);
        // Moving the slave node by delta towards the master uses delta of the gap.
        std::vector<double> u(s.coords.size(), 0.0);
        u[2 * s.slaves[k]] = -0.01 * nx;
        u[2 * s.slaves[k] + 1] = -0.01 * ny;
        TEST_FLOATING_EQUALITY(applyRow(row, u), 0.01, 1e-12);
      }
      // The current geometry x + u: slave nodes moved 0.02 towards the master, the master 0.01
      // away from them, and everything shifted along the surface.
      std::vector<double> u(s.coords.size(), 0.0);
      for (std::size_t n = 0; n < s.coords.size() / 2; ++n) {
        const bool slave = std::find(s.slaves.begin(), s.slaves.end(), n) != s.slaves.end();
        const double normalShift = slave ? -0.02 : -0.01;
        u[2 * n] = normalShift * nx + 0.001 * ny;
        u[2 * n + 1] = normalShift * ny - 0.001 * nx;
      }
      const NodeToSegmentResult moved =
          computeNodeToSegment(s.coords, s.slaves, s.master, radius(0.2), u);
      TEST_EQUALITY(moved.rows.size(), xs.size());
      for (const auto& row : moved.rows) TEST_FLOATING_EQUALITY(row.gap, d - 0.01, 1e-12);
      // Penetration: a negative gap.
      for (std::size_t n : s.slaves) u[2 * n] = -0.07 * nx, u[2 * n + 1] = -0.07 * ny;
      const NodeToSegmentResult pen =
          computeNodeToSegment(s.coords, s.slaves, s.master, radius(0.2), u);
      TEST_EQUALITY(pen.rows.size(), xs.size());
      for (const auto& row : pen.rows) TEST_FLOATING_EQUALITY(row.gap, d - 0.06, 1e-12);
    }
}

TEUCHOS_UNIT_TEST(NodeToSegment, CircleGapConvergence) {
  const std::vector<int> ns{16, 32, 64, 128};
  std::vector<double> lin, quad, linNormal, quadNormal;
  for (int n : ns) {
    const CircleErrors l = circleErrors(n, 2), q = circleErrors(n, 3);
    out << "n = " << n << ": gap error linear " << l.gap << ", quadratic " << q.gap
        << "; normal error linear " << l.normal << ", quadratic " << q.normal
        << "; at master nodes " << l.atNodes << ", " << q.atNodes << " (corners " << l.corners
        << ", " << q.corners << "); |B rotation| " << l.rotation << ", " << q.rotation << "\n";
    TEST_EQUALITY(l.rows, 997);
    TEST_EQUALITY(q.rows, 997);
    // Exact where a slave node lies on the ray of a master node (the corner of the polygon).
    TEST_COMPARE(l.atNodes, <, 1e-13);
    TEST_COMPARE(q.atNodes, <, 1e-13);
    TEST_EQUALITY(l.corners, n);
    TEST_EQUALITY(q.corners, n);
    // Linear: the chord's sagitta R (1 - cos(pi/n)) bounds the error.
    TEST_COMPARE(l.gap, <=, 1.0 * (1.0 - std::cos(kPi / n)) + 1e-15);
    TEST_COMPARE(l.gap, >, 0.5 * (1.0 - std::cos(kPi / n)));
    TEST_COMPARE(q.gap, <, 0.1 * l.gap);
    TEST_COMPARE(l.rotation, <, 1e-13);
    TEST_COMPARE(q.rotation, <, 1e-13);
    lin.push_back(l.gap);
    linNormal.push_back(l.normal);
    quadNormal.push_back(q.normal);
    quad.push_back(q.gap);
  }
  for (std::size_t i = 1; i < ns.size(); ++i) {
    const double pl = std::log2(lin[i - 1] / lin[i]), pq = std::log2(quad[i - 1] / quad[i]);
    out << "order " << ns[i - 1] << " -> " << ns[i] << ": linear " << pl << ", quadratic " << pq
        << "\n";
    TEST_COMPARE(std::abs(pl - 2.0), <, 0.15);
    TEST_COMPARE(pq, >, 3.7);
    // Normals: the chord's direction is O(h) off, the parabola's O(h^3).
    const double nl = std::log2(linNormal[i - 1] / linNormal[i]);
    const double nq = std::log2(quadNormal[i - 1] / quadNormal[i]);
    out << "normal order: linear " << nl << ", quadratic " << nq << "\n";
    TEST_COMPARE(std::abs(nl - 1.0), <, 0.1);
    TEST_COMPARE(nq, >, 2.8);
  }
}

TEUCHOS_UNIT_TEST(NodeToSegment, CornersConvexAndConcave) {
  // Convex: the top right corner of the unit square (body inside), walked up the right side
  // and leftwards along the top.
  Setup s;
  for (const auto& [x, y] :
       std::vector<std::array<double, 2>>{{1, 0}, {1, 0.5}, {1, 1}, {0.5, 1}, {0, 1}})
    s.add(x, y);
  s.master.segments = {0, 1, 1, 2, 2, 3, 3, 4};  // corner: node 2
  const int diag = s.add(1.1, 1.1), onRay = s.add(1.1, 1.0), onCorner = s.add(1.0, 1.0),
            inside = s.add(0.97, 0.98), skew = s.add(1.1, 1.05);
  const NodeToSegmentResult r =
      computeNodeToSegment(s.coords, {diag, onRay, onCorner, inside, skew}, s.master, radius(0.3));
  TEST_EQUALITY(r.rows.size(), 5u);
  if (r.rows.size() == 5) {
    // Off the diagonal the normal is the direction to the node, not the average one.
    TEST_EQUALITY(static_cast<int>(r.rows[4].kind), static_cast<int>(ProjectionKind::Corner));
    TEST_FLOATING_EQUALITY(r.rows[4].gap, std::hypot(0.1, 0.05), 1e-13);
    TEST_FLOATING_EQUALITY(r.rows[4].normal[0], 0.1 / std::hypot(0.1, 0.05), 1e-13);
    TEST_FLOATING_EQUALITY(r.rows[4].normal[1], 0.05 / std::hypot(0.1, 0.05), 1e-13);
    TEST_COMPARE(std::abs(applyRow(r.rows[4], rigid(s.coords, 0, 0, 1.0, 2.0, 5.0))), <, 1e-14);
    const double h = std::sqrt(0.5);
    TEST_EQUALITY(static_cast<int>(r.rows[0].kind), static_cast<int>(ProjectionKind::Corner));
    TEST_FLOATING_EQUALITY(r.rows[0].gap, std::sqrt(0.02), 1e-13);
    TEST_FLOATING_EQUALITY(r.rows[0].normal[0], h, 1e-14);
    TEST_FLOATING_EQUALITY(r.rows[0].normal[1], h, 1e-14);
    TEST_COMPARE(std::abs(applyRow(r.rows[0], rigid(s.coords, 0, 0, 1.0, -3.0, 2.0))), <, 1e-14);
    // The corner's weight is all on the corner node.
    for (const auto& e : r.rows[0].entries)
      if (e.node != diag && e.node != 2) TEST_EQUALITY(e.coef, 0.0);
    TEST_FLOATING_EQUALITY(r.rows[1].gap, 0.1, 1e-13);
    TEST_COMPARE(std::abs(r.rows[1].normal[0] - 1.0), <, 1e-14);
    TEST_COMPARE(std::abs(r.rows[1].normal[1]), <, 1e-14);
    // On the corner node: no direction to the node, the average normal.
    TEST_EQUALITY(static_cast<int>(r.rows[2].kind), static_cast<int>(ProjectionKind::Corner));
    TEST_COMPARE(std::abs(r.rows[2].gap), <, 1e-15);
    TEST_FLOATING_EQUALITY(r.rows[2].normal[0], h, 1e-14);
    TEST_FLOATING_EQUALITY(r.rows[2].normal[1], h, 1e-14);
    // Penetrated: the nearer side (the top) wins.
    TEST_EQUALITY(r.rows[3].facet, 2);
    TEST_FLOATING_EQUALITY(r.rows[3].gap, -0.02, 1e-12);
    TEST_COMPARE(std::abs(r.rows[3].normal[1] - 1.0), <, 1e-14);
  }
  // On the corner up to noise (1e-12 along the right side): the average normal, not the
  // direction of the noise (kCornerSnap), so that the row does not turn into a symmetry row.
  const int noisy = s.add(1.0 + 1e-13, 1.0 + 1e-12);
  const NodeToSegmentResult rn = computeNodeToSegment(s.coords, {noisy}, s.master, radius(0.3));
  TEST_EQUALITY(rn.rows.size(), 1u);
  if (rn.rows.size() == 1) {
    TEST_EQUALITY(static_cast<int>(rn.rows[0].kind), static_cast<int>(ProjectionKind::Corner));
    TEST_FLOATING_EQUALITY(rn.rows[0].normal[0], std::sqrt(0.5), 1e-14);
    TEST_FLOATING_EQUALITY(rn.rows[0].normal[1], std::sqrt(0.5), 1e-14);
  }
  // Concave: the re-entrant corner (1, 1) of the L = (0,2)x(0,1) u (0,1)x(0,2), walked leftwards
  // along y = 1 and then up x = 1.
  Setup l;
  for (const auto& [x, y] :
       std::vector<std::array<double, 2>>{{2, 1}, {1.5, 1}, {1, 1}, {1, 1.5}, {1, 2}})
    l.add(x, y);
  l.master.segments = {0, 1, 1, 2, 2, 3, 3, 4};
  const int deep = l.add(0.95, 0.95);
  const NodeToSegmentResult c = computeNodeToSegment(l.coords, {deep}, l.master, radius(0.3));
  TEST_EQUALITY(c.rows.size(), 1u);
  if (c.rows.size() == 1) {
    TEST_EQUALITY(static_cast<int>(c.rows[0].kind), static_cast<int>(ProjectionKind::Corner));
    TEST_FLOATING_EQUALITY(c.rows[0].normal[0], std::sqrt(0.5), 1e-14);
    TEST_FLOATING_EQUALITY(c.rows[0].normal[1], std::sqrt(0.5), 1e-14);
    TEST_FLOATING_EQUALITY(c.rows[0].gap, -0.05 * std::sqrt(2.0), 1e-12);
  }
}

TEUCHOS_UNIT_TEST(NodeToSegment, NodeOnAVertexTakesTheAveragedNormalFromEitherSide) {
  // A slightly concave master (a flat top deformed by the load): a node on its vertex, up to
  // rounding on either side, projects into both segments' interiors, and the nearer segment
  // depends on the rounding. Both sides give the corner's averaged normal and the same entries
  // (kVertexSnap); away from the vertex each segment keeps its own normal.
  Setup s;
  for (const auto& [x, y] : std::vector<std::array<double, 2>>{{1, 0.02}, {0, 0}, {-1, 0.01}})
    s.add(x, y);
  s.master.segments = {0, 1, 1, 2};  // vertex: node 1
  const int left = s.add(-1e-13, 1e-15), right = s.add(1e-13, 1e-15);
  const int inRight = s.add(0.5, 0.01), inLeft = s.add(-0.5, 0.005);
  const NodeToSegmentResult r =
      computeNodeToSegment(s.coords, {left, right, inRight, inLeft}, s.master, radius(0.3));
  TEST_EQUALITY(r.rows.size(), 4u);
  if (r.rows.size() != 4) return;
  const auto& a = r.rows[2].normal;
  const auto& b = r.rows[3].normal;
  TEST_COMPARE(std::abs(a[0] - b[0]), >, 1e-3);  // the two segments' own normals differ
  const double sx = a[0] + b[0], sy = a[1] + b[1], len = std::hypot(sx, sy);
  for (int k : {0, 1}) {
    TEST_EQUALITY(static_cast<int>(r.rows[k].kind), static_cast<int>(ProjectionKind::Corner));
    TEST_FLOATING_EQUALITY(r.rows[k].normal[0], sx / len, 1e-12);
    TEST_FLOATING_EQUALITY(r.rows[k].normal[1], sy / len, 1e-12);
    for (const auto& e : r.rows[k].entries)
      if (e.node != 1 && e.node != left && e.node != right) TEST_EQUALITY(e.coef, 0.0);
  }
}

TEUCHOS_UNIT_TEST(NodeToSegment, SearchRadius) {
  for (int nps : {2, 3}) {
    Setup s = circleMaster(32, nps, 1.0);
    const int near = s.add(1.05, 0.01), far = s.add(0.0, -1.5), centre = s.add(0.0, 0.0),
              justOut = s.add(-1.21, 0.0), inside = s.add(0.0, 0.96);
    const NodeToSegmentResult r =
        computeNodeToSegment(s.coords, {near, far, centre, justOut, inside}, s.master, radius(0.2));
    TEST_EQUALITY(r.rows.size(), 2u);
    TEST_EQUALITY(r.beyondRadius, 3);
    TEST_EQUALITY(r.beyondEnd, 0);
    if (r.rows.size() != 2) continue;
    TEST_EQUALITY(r.rows[0].slaveNode, near);
    TEST_EQUALITY(r.rows[1].slaveNode, inside);
    TEST_COMPARE(std::abs(r.rows[0].gap - 0.05), <, 0.01);
    TEST_COMPARE(std::abs(r.rows[1].gap + 0.04), <, 0.01);
    // The same nodes with a radius taking in justOut.
    const NodeToSegmentResult wide =
        computeNodeToSegment(s.coords, {justOut}, s.master, radius(0.22));
    TEST_EQUALITY(wide.rows.size(), 1u);
  }
}

TEUCHOS_UNIT_TEST(NodeToSegment, FreeEndsDropOrClamp) {
  for (int nps : {2, 3}) {
    Setup s = flatMaster(10, nps);
    // Before the start (x < 0), exactly opposite both ends, inside, after the end, and beyond
    // the end farther than the radius from the end point.
    const std::vector<double> xs{-0.2, 0.0, 0.55, 1.0, 1.3, 1.6};
    for (double x : xs) s.slaves.push_back(s.add(x, 0.05));
    const NodeToSegmentResult drop =
        computeNodeToSegment(s.coords, s.slaves, s.master, radius(0.5, EndPolicy::Drop));
    TEST_EQUALITY(drop.rows.size(), 3u);
    TEST_EQUALITY(drop.beyondEnd, 2);
    TEST_EQUALITY(drop.beyondRadius, 1);
    if (drop.rows.size() == 3) {
      TEST_EQUALITY(drop.rows[0].slaveNode, s.slaves[1]);
      TEST_EQUALITY(drop.rows[1].slaveNode, s.slaves[2]);
      TEST_EQUALITY(drop.rows[2].slaveNode, s.slaves[3]);
      // x = 0 is the second node of the last segment, x = 1 the first of the first.
      TEST_EQUALITY(drop.rows[0].facet, 9);
      TEST_EQUALITY(drop.rows[0].xi[0], 1.0);
      TEST_EQUALITY(drop.rows[2].facet, 0);
      TEST_EQUALITY(drop.rows[2].xi[0], -1.0);
      for (const auto& row : drop.rows) {
        TEST_EQUALITY(static_cast<int>(row.kind), static_cast<int>(ProjectionKind::Interior));
        TEST_FLOATING_EQUALITY(row.gap, 0.05, 1e-12);
      }
    }
    const NodeToSegmentResult clamp =
        computeNodeToSegment(s.coords, s.slaves, s.master, radius(0.5, EndPolicy::Clamp));
    TEST_EQUALITY(clamp.rows.size(), 5u);
    TEST_EQUALITY(clamp.beyondEnd, 0);
    TEST_EQUALITY(clamp.beyondRadius, 1);
    if (clamp.rows.size() == 5) {
      for (int k : {0, 4}) {
        const NodeToSegmentRow& row = clamp.rows[k];
        TEST_EQUALITY(static_cast<int>(row.kind), static_cast<int>(ProjectionKind::End));
        TEST_EQUALITY(row.xi[0], k == 0 ? 1.0 : -1.0);
        TEST_EQUALITY(row.facet, k == 0 ? 9 : 0);
        // The distance to the master's tangent line, with its normal.
        TEST_FLOATING_EQUALITY(row.gap, 0.05, 1e-12);
        TEST_COMPARE(std::abs(row.normal[0]), <, 1e-15);
        TEST_COMPARE(std::abs(row.normal[1] - 1.0), <, 1e-15);
        TEST_COMPARE(std::abs(row.point[0] - (k == 0 ? 0.0 : 1.0)), <, 1e-15);
      }
    }
  }
}

TEUCHOS_UNIT_TEST(NodeToSegment, BucketSearchMatchesAllPairs) {
  // A wavy master y = 0.2 sin x over (0, 20) of 2000 segments, body below, and 2000 slave nodes
  // 0.01 above it at other abscissae.
  for (int nps : {2, 3}) {
    const int n = 2000;
    Setup s;
    s.master.nodesPerSegment = nps;
    auto f = [](double x) { return 0.2 * std::sin(x); };
    for (int i = 0; i <= n; ++i) {
      const double x = 20.0 * i / n;
      s.add(x, f(x));
    }
    for (int i = n; i > 0; --i) {
      s.master.segments.insert(s.master.segments.end(), {i, i - 1});
      if (nps == 3) {
        const double x = 20.0 * (i - 0.5) / n;
        s.master.segments.push_back(s.add(x, f(x)));
      }
    }
    for (int k = 0; k < n; ++k) {
      const double x = 20.0 * (k + 0.3) / n;
      s.slaves.push_back(s.add(x, f(x) + 0.01 + 0.004 * std::sin(7.0 * x)));
    }
    const NodeToSegmentResult grid =
        computeNodeToSegment(s.coords, s.slaves, s.master, radius(0.05));
    NodeToSegmentOptions all = radius(0.05);
    all.bruteForce = true;
    const NodeToSegmentResult ref = computeNodeToSegment(s.coords, s.slaves, s.master, all);
    out << "nodesPerSegment " << nps << ": candidate pairs " << grid.candidatePairs << " of "
        << grid.allPairs << " (" << 100.0 * grid.candidatePairs / grid.allPairs << " %), cells "
        << grid.gridCells << " of size " << grid.cellSize << "; all-pairs search "
        << ref.candidatePairs << "\n";
    TEST_EQUALITY(grid.allPairs, 4000000LL);
    TEST_EQUALITY(ref.candidatePairs, 4000000LL);
    TEST_COMPARE(grid.candidatePairs, <, 20LL * n);
    TEST_COMPARE(grid.candidatePairs, >=, static_cast<long long>(n));
    TEST_EQUALITY(grid.rows.size(), static_cast<std::size_t>(n));
    TEST_EQUALITY(grid.rows.size(), ref.rows.size());
    if (grid.rows.size() != ref.rows.size()) continue;
    int differ = 0;
    double minGap = 1.0, maxGap = 0.0;
    for (std::size_t k = 0; k < grid.rows.size(); ++k) {
      const auto &a = grid.rows[k], &b = ref.rows[k];
      differ += a.slaveNode != b.slaveNode || a.facet != b.facet || a.xi != b.xi || a.gap != b.gap;
      minGap = std::min(minGap, a.gap);
      maxGap = std::max(maxGap, a.gap);
    }
    TEST_EQUALITY(differ, 0);
    // The vertical offset 0.006 .. 0.014 over a slope of at most 0.2 (cos > 0.98).
    TEST_COMPARE(minGap, >, 0.0058);
    TEST_COMPARE(maxGap, <, 0.0141);
  }
}

TEUCHOS_UNIT_TEST(NodeToSegment, OrientationErrorsDetectedAndCorrected) {
  for (int nps : {2, 3}) {
    const int n = 32;
    Setup s = circleMaster(n, nps, 1.0);
    for (int k = 0; k < 40; ++k) {
      const double a = 2 * kPi * (k + 0.21) / 40;
      s.slaves.push_back(s.add(1.03 * std::cos(a), 1.03 * std::sin(a)));
    }
    const NodeToSegmentResult good =
        computeNodeToSegment(s.coords, s.slaves, s.master, radius(0.1));
    TEST_EQUALITY(good.rows.size(), 40u);
    TEST_EQUALITY(contact::findOrientationErrors(s.master).size(), 0u);

    // Two segments reversed: their end nodes see two starts or two ends.
    MasterSurface flipped = s.master;
    for (int seg : {5, 17}) std::swap(flipped.segments[nps * seg], flipped.segments[nps * seg + 1]);
    const std::vector<int> bad = contact::findOrientationErrors(flipped);
    TEST_COMPARE_ARRAYS(bad, std::vector<int>({5, 6, 17, 18}));
    TEST_THROW(computeNodeToSegment(s.coords, s.slaves, flipped, radius(0.1)),
               std::invalid_argument);

    // Corrected from the body's elements, whichever way the elements run.
    for (bool clockwise : {false, true}) {
      Setup withFan = s;
      const std::vector<int> fan = circleFan(withFan, n, clockwise);
      MasterSurface fixed = flipped;
      const contact::ElementType type =
          nps == 2 ? contact::ElementType::Tri3 : contact::ElementType::Tri6;
      // (Called outside the macros, which evaluate their arguments more than once.)
      const int flips = contact::orientSegmentsByElements(fixed, withFan.coords, type, fan);
      TEST_EQUALITY(flips, 2);
      TEST_COMPARE_ARRAYS(fixed.segments, s.master.segments);
      // A consistently reversed surface is only detectable with the body.
      MasterSurface reversed = s.master;
      for (int seg = 0; seg < n; ++seg)
        std::swap(reversed.segments[nps * seg], reversed.segments[nps * seg + 1]);
      TEST_EQUALITY(contact::findOrientationErrors(reversed).size(), 0u);
      const NodeToSegmentResult wrong =
          computeNodeToSegment(s.coords, s.slaves, reversed, radius(0.1));
      TEST_EQUALITY(wrong.rows.size(), 40u);
      if (!wrong.rows.empty()) TEST_COMPARE(wrong.rows[0].gap, <, 0.0);
      const int all = contact::orientSegmentsByElements(reversed, withFan.coords, type, fan);
      TEST_EQUALITY(all, n);
      TEST_COMPARE_ARRAYS(reversed.segments, s.master.segments);
    }
    // From a point inside (the disc is star-shaped about its centre).
    MasterSurface fixed = flipped;
    const int flips = contact::orientSegmentsTowardPoint(fixed, s.coords, 0.01, -0.02);
    TEST_EQUALITY(flips, 2);
    TEST_COMPARE_ARRAYS(fixed.segments, s.master.segments);
    const NodeToSegmentResult again = computeNodeToSegment(s.coords, s.slaves, fixed, radius(0.1));
    TEST_EQUALITY(again.rows.size(), good.rows.size());
    int differ = 0;
    for (std::size_t k = 0; k < std::min(again.rows.size(), good.rows.size()); ++k)
      differ += again.rows[k].gap != good.rows[k].gap || again.rows[k].facet != good.rows[k].facet;
    TEST_EQUALITY(differ, 0);
    // An element list without one of the segments' edges is an error, as is a point on a
    // segment's line.
    Setup partial = s;
    std::vector<int> fan = circleFan(partial, n, false);
    fan.resize(fan.size() - (nps == 2 ? 3 : 6));
    MasterSurface m = s.master;
    TEST_THROW(contact::orientSegmentsByElements(
                   m, partial.coords,
                   nps == 2 ? contact::ElementType::Tri3 : contact::ElementType::Tri6, fan),
               std::invalid_argument);
    // On the line of segment 0's chord, from (1, 0) to node 1, one chord length before (1, 0).
    TEST_THROW(contact::orientSegmentsTowardPoint(m, s.coords, 2.0 - s.coords[2], -s.coords[3]),
               std::invalid_argument);
  }
}

TEUCHOS_UNIT_TEST(NodeToSegment, InvalidInputAndInequalityRow) {
  Setup s = flatMaster(4, 2);
  s.slaves.push_back(s.add(0.3, 0.1));
  TEST_THROW(computeNodeToSegment(s.coords, s.slaves, s.master, radius(0.0)),
             std::invalid_argument);
  TEST_THROW(computeNodeToSegment(s.coords, {99}, s.master, radius(1.0)), std::invalid_argument);
  TEST_THROW(computeNodeToSegment(s.coords, s.slaves, s.master, radius(1.0), {1.0, 2.0}),
             std::invalid_argument);
  MasterSurface odd = s.master;
  odd.nodesPerSegment = 3;
  TEST_THROW(computeNodeToSegment(s.coords, s.slaves, odd, radius(1.0)), std::invalid_argument);
  MasterSurface outOfRange = s.master;
  outOfRange.segments[3] = 1000;
  TEST_THROW(computeNodeToSegment(s.coords, s.slaves, outOfRange, radius(1.0)),
             std::invalid_argument);

  const NodeToSegmentResult r = computeNodeToSegment(s.coords, s.slaves, s.master, radius(1.0));
  TEST_EQUALITY(r.rows.size(), 1u);
  if (r.rows.size() != 1) return;
  // Node n lives in subdomain n / 3 at local dofs 2 (n % 3) + component.
  const tfeti::InequalityRow row = contact::toInequalityRow(
      r.rows[0], [](int node, int c) { return std::make_pair(node / 3, 2 * (node % 3) + c); });
  TEST_FLOATING_EQUALITY(row.gap, 0.1, 1e-12);
  // The x coefficients vanish on a master along x and are left out.
  TEST_EQUALITY(row.entries.size(), 3u);
  double sum = 0.0;
  for (const auto& e : row.entries) {
    TEST_EQUALITY(e.dof % 2, 1);
    sum += e.coef;
  }
  TEST_COMPARE(std::abs(sum), <, 1e-15);
  TEST_EQUALITY(row.entries[0].subdomain, s.slaves[0] / 3);
  TEST_FLOATING_EQUALITY(row.entries[0].coef, -1.0, 1e-15);
}

}  // namespace
