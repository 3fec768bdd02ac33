// Dual mortar contact (contact_Mortar.hpp): D and M against hand-integrated values, the dual
// basis' biorthogonality on whole and partially covered facets, clipping of degenerate
// overlaps, weighted gaps that reproduce linear fields (the discrete patch property) on
// non-matching 2D and 3D surfaces, matching meshes giving node-to-segment's rows, and a rigid
// obstacle's weighted gap.
#include <Teuchos_UnitTestHarness.hpp>

#include <cmath>
#include <map>
#include <vector>

#include "contact_Mortar.hpp"
#include "contact_MortarIntegration.hpp"
#include "contact_RigidObstacle.hpp"

namespace {

using contact::ElementType;
using contact::MortarSurface;

ElementType kFacetTypes[] = {ElementType::Line2, ElementType::Line3, ElementType::Tri3,
                             ElementType::Tri6,  ElementType::Quad4, ElementType::Quad8,
                             ElementType::Quad9};

// sum_q w phi_j N_b against delta_jb sum_q w N_j for the rule q on the multiplier space of t.
double biorthogonalityDefect(ElementType t, const contact::PlaneQuadrature& q) {
  const auto lm = contact::multiplierSpace(t);
  const int n = lm.count;
  std::vector<double> N;
  double v[9];
  for (const auto& p : q.points) {
    contact::multiplierShapeFunctions(lm, p.data(), v);
    N.insert(N.end(), v, v + n);
  }
  const auto A = contact::dualBasisCoefficients(n, q.weights, N);
  if (A.empty()) return 1e300;
  double defect = 0.0, scale = 0.0;
  for (int j = 0; j < n; ++j) {
    double share = 0.0;
    for (std::size_t k = 0; k < q.weights.size(); ++k) share += q.weights[k] * N[k * n + j];
    scale = std::max(scale, std::abs(share));
    for (int b = 0; b < n; ++b) {
      double s = 0.0;
      for (std::size_t k = 0; k < q.weights.size(); ++k) {
        double phi = 0.0;
        for (int c = 0; c < n; ++c) phi += A[j * n + c] * N[k * n + c];
        s += q.weights[k] * phi * N[k * n + b];
      }
      defect = std::max(defect, std::abs(s - (j == b ? share : 0.0)));
    }
  }
  return defect / scale;
}

TEUCHOS_UNIT_TEST(Mortar, DualBasisIsBiorthogonal) {
  for (ElementType t : kFacetTypes) {
    out << contact::elementTypeName(t) << ": whole facet\n";
    TEST_COMPARE(biorthogonalityDefect(t, contact::referenceFacetQuadrature(t)), <, 1e-13);
    // A covered part: a sub-interval, or a polygon inside the reference facet.
    contact::PlaneQuadrature part;
    if (contact::facetParametricDimension(t) == 1)
      part = contact::intervalQuadrature(-0.3, 1.0);
    else if (t == ElementType::Tri3 || t == ElementType::Tri6)
      part = contact::polygonQuadrature({{0.1, 0.0}, {0.8, 0.0}, {0.3, 0.6}, {0.05, 0.4}});
    else
      part = contact::polygonQuadrature({{-1.0, -0.2}, {0.6, -1.0}, {1.0, 1.0}, {-0.5, 0.9}});
    out << contact::elementTypeName(t) << ": covered part\n";
    TEST_COMPARE(biorthogonalityDefect(t, part), <, 1e-12);
  }
  // A sliver: one point cannot carry a dual basis of two functions.
  contact::PlaneQuadrature one;
  one.points = {{0.2, 0.0}};
  one.weights = {1.0};
  std::vector<double> N = {0.4, 0.6};
  TEST_ASSERT(contact::dualBasisCoefficients(2, one.weights, N).empty());
}

// Tri6 and Quad8 multipliers: the modified quadratic functions sum to one, take at the facet's
// nodes the values that define them (a corner's: 1 at its corner, alpha at the midsides of its
// two edges, told apart geometrically, 0 elsewhere; a midside's: 1 - 2 alpha at its node), and
// each integrates to the positive share the dual basis needs.
TEUCHOS_UNIT_TEST(Mortar, ModifiedQuadraticMultipliers) {
  const double tri[6][2] = {{0, 0}, {1, 0}, {0, 1}, {0.5, 0}, {0.5, 0.5}, {0, 0.5}};
  const double quad[8][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}, {0, -1}, {1, 0}, {0, 1}, {-1, 0}};
  for (ElementType t : {ElementType::Tri6, ElementType::Quad8}) {
    const auto lm = contact::multiplierSpace(t);
    TEST_EQUALITY(lm.count, contact::numNodes(t));
    TEST_FLOATING_EQUALITY(lm.alpha, 0.2, 1e-15);
    const int corners = t == ElementType::Tri6 ? 3 : 4;
    auto node = [&](int a) { return t == ElementType::Tri6 ? tri[a] : quad[a]; };
    for (int b = 0; b < lm.count; ++b) {
      double v[9];
      contact::multiplierShapeFunctions(lm, node(b), v);
      for (int a = 0; a < lm.count; ++a) {
        double want = a == b ? (a < corners ? 1.0 : 1.0 - 2.0 * lm.alpha) : 0.0;
        if (a < corners && b >= corners) {
          // Midside b lies on an edge of corner a when it is the midpoint of a and a corner.
          for (int c = 0; c < corners; ++c)
            if (c != a && std::abs(0.5 * (node(a)[0] + node(c)[0]) - node(b)[0]) < 1e-15 &&
                std::abs(0.5 * (node(a)[1] + node(c)[1]) - node(b)[1]) < 1e-15)
              want = lm.alpha;
        }
        TEST_COMPARE(std::abs(v[a] - want), <, 1e-14);
      }
    }
    const auto q = contact::referenceFacetQuadrature(t);
    std::vector<double> share(lm.count, 0.0);
    double total = 0.0, v[9];
    for (std::size_t k = 0; k < q.weights.size(); ++k) {
      contact::multiplierShapeFunctions(lm, q.points[k].data(), v);
      double sum = 0.0;
      for (int a = 0; a < lm.count; ++a) sum += v[a], share[a] += q.weights[k] * v[a];
      TEST_FLOATING_EQUALITY(sum, 1.0, 1e-14);
      total += q.weights[k];
    }
    const double corner = t == ElementType::Tri6 ? 2.0 / 15.0 : 1.0 / 20.0;
    for (int a = 0; a < lm.count; ++a)
      TEST_FLOATING_EQUALITY(share[a] / total, a < corners ? corner : 0.2, 1e-13);
  }
}

TEUCHOS_UNIT_TEST(Mortar, ClippingOfDegenerateOverlaps) {
  const contact::Polygon unit = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  // The same square, one inside, one sharing only an edge, one only a vertex, one apart.
  TEST_FLOATING_EQUALITY(contact::polygonArea(contact::clipPolygon(unit, unit, 1e-12)), 1.0, 1e-14);
  const contact::Polygon inner = {{0.2, 0.2}, {0.6, 0.3}, {0.4, 0.7}};
  TEST_FLOATING_EQUALITY(contact::polygonArea(contact::clipPolygon(inner, unit, 1e-12)),
                         contact::polygonArea(inner), 1e-14);
  const contact::Polygon edge = {{1, 0}, {2, 0}, {2, 1}, {1, 1}};
  TEST_ASSERT(contact::clipPolygon(edge, unit, 1e-12).empty());
  const contact::Polygon vertex = {{1, 1}, {2, 1}, {2, 2}, {1, 2}};
  TEST_ASSERT(contact::clipPolygon(vertex, unit, 1e-12).empty());
  const contact::Polygon apart = {{3, 3}, {4, 3}, {4, 4}};
  TEST_ASSERT(contact::clipPolygon(apart, unit, 1e-12).empty());
  // A square turned by 45 degrees about the unit square's centre: an octagon of area
  // 1 - 4 * (corner triangles) with half-diagonal 1/sqrt(2): area 2 (sqrt 2 - 1).
  const double h = 0.5 * std::sqrt(2.0);
  const contact::Polygon diamond = {{0.5, 0.5 - h}, {0.5 + h, 0.5}, {0.5, 0.5 + h}, {0.5 - h, 0.5}};
  const auto oct = contact::clipPolygon(diamond, unit, 1e-12);
  TEST_EQUALITY(oct.size(), std::size_t(8));
  TEST_FLOATING_EQUALITY(contact::polygonArea(oct), 2.0 * (std::sqrt(2.0) - 1.0), 1e-13);
}

// 2D by hand: slave Line2 between (0, 0) and (1, 0) (body below, normal +y), master Line2
// between (0.5, 0.1) and (1.5, 0.1) (body above, normal -y); a body is on the left of a -> b. The
// covered part is x in [0.5, 1]; there M = [[1/24, 1/12], [1/12, 7/24]], D = diag(1/8, 3/8), phi_0
// = 7 - 9x, phi_1 = 9x - 6, and int phi_j N^m_k = [[3/16, -1/16], [3/16, 3/16]].
TEUCHOS_UNIT_TEST(Mortar, HandIntegrated2D) {
  const std::vector<double> x = {0.0, 0.0, 1.0, 0.0, 1.5, 0.1, 0.5, 0.1};
  MortarSurface slave{2, ElementType::Line2, {1, 0}};
  MortarSurface master{2, ElementType::Line2, {3, 2}};
  const auto c = contact::mortarCouplings(x, slave, master, 1.0);
  TEST_EQUALITY(c.byNode.size(), std::size_t(2));
  const auto& c0 = c.byNode.at(0);
  const auto& c1 = c.byNode.at(1);
  TEST_FLOATING_EQUALITY(c0.slave.at(0), 1.0 / 8.0, 1e-13);
  TEST_COMPARE(std::abs(c0.slave.at(1)), <, 1e-14);
  TEST_COMPARE(std::abs(c1.slave.at(0)), <, 1e-14);
  TEST_FLOATING_EQUALITY(c1.slave.at(1), 3.0 / 8.0, 1e-13);
  // Master node 3 is at x = 0.5 (N^m = 1.5 - x), node 2 at x = 1.5 (N^m = x - 0.5).
  TEST_FLOATING_EQUALITY(c0.master.at(3), 3.0 / 16.0, 1e-13);
  TEST_FLOATING_EQUALITY(c0.master.at(2), -1.0 / 16.0, 1e-13);
  TEST_FLOATING_EQUALITY(c1.master.at(3), 3.0 / 16.0, 1e-13);
  TEST_FLOATING_EQUALITY(c1.master.at(2), 3.0 / 16.0, 1e-13);
  TEST_FLOATING_EQUALITY(c0.weight, 1.0 / 8.0, 1e-13);
  TEST_FLOATING_EQUALITY(c1.weight, 3.0 / 8.0, 1e-13);
  // The rows: gap 0.1 (the weighted gap of two parallel lines), normal -y (master to slave).
  contact::ContactSearchOptions o;
  o.searchRadius = 1.0;
  const auto m = contact::makeMortarMaster(slave, master, o);
  const auto r = m->rows(x, {0, 1});
  TEST_EQUALITY(r.rows.size(), std::size_t(2));
  for (const auto& row : r.rows) {
    TEST_FLOATING_EQUALITY(row.gap, 0.1, 1e-13);
    TEST_FLOATING_EQUALITY(row.normal[1], -1.0, 1e-14);
    TEST_EQUALITY(row.entries.size(), std::size_t(2 * 3));    // the node and two master nodes
    TEST_FLOATING_EQUALITY(row.entries[1].coef, 1.0, 1e-14);  // -(D_jj / W_j) n_y
  }
}

// A flat slave surface of nx x ny Quad4 (or Tri3) facets on z = 0 against a master surface of
// another, rotated, grid of facets on z = h: every weighted-gap integral reproduces linear
// fields, so each row's gap is h, D is diagonal, sum_j M_jk = int N^m_k over the covered part and
// sum_k M_jk = W_j.
struct Grid {
  std::vector<double> x;
  MortarSurface s;
};

void addGrid(Grid& g, int n, double size, double angle, double cx, double cy, double z, bool up,
             bool triangles) {
  const int base = static_cast<int>(g.x.size()) / 3;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      const double u = -0.5 * size + size * i / n, v = -0.5 * size + size * j / n;
      g.x.insert(g.x.end(), {cx + std::cos(angle) * u - std::sin(angle) * v,
                             cy + std::sin(angle) * u + std::cos(angle) * v, z});
    }
  g.s.dim = 3;
  g.s.type = triangles ? ElementType::Tri3 : ElementType::Quad4;
  auto id = [&](int i, int j) { return base + j * (n + 1) + i; };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      std::vector<int> q = {id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)};
      if (!up) q = {q[0], q[3], q[2], q[1]};  // outward -z
      if (triangles) {
        g.s.facets.insert(g.s.facets.end(), {q[0], q[1], q[2]});
        g.s.facets.insert(g.s.facets.end(), {q[0], q[2], q[3]});
      } else {
        g.s.facets.insert(g.s.facets.end(), q.begin(), q.end());
      }
    }
}

TEUCHOS_UNIT_TEST(Mortar, NonMatching3DReproducesLinearFields) {
  for (bool triangles : {false, true}) {
    Grid slave, master;
    addGrid(slave, 4, 1.0, 0.0, 0.0, 0.0, 0.0, true, false);
    master.x = slave.x;
    addGrid(master, 7, 2.0, 0.3, 0.05, -0.02, 0.02, false, triangles);
    const auto c = contact::mortarCouplings(master.x, slave.s, master.s, 0.5);
    TEST_EQUALITY(c.byNode.size(), std::size_t(25));
    TEST_EQUALITY(c.singularFacets, 0);
    double total = 0.0;
    for (const auto& [j, cj] : c.byNode) {
      total += cj.weight;
      double sumM = 0.0, fx = 0.0, fy = 0.0;
      for (const auto& [k, m] : cj.master) {
        sumM += m;
        fx += m * master.x[3 * k];
        fy += m * master.x[3 * k + 1];
      }
      double dx = 0.0, dy = 0.0;
      for (const auto& [a, d] : cj.slave) {
        if (a != j) TEST_COMPARE(std::abs(d), <, 1e-13);
        dx += d * master.x[3 * a];
        dy += d * master.x[3 * a + 1];
      }
      TEST_FLOATING_EQUALITY(sumM, cj.weight, 1e-12);
      TEST_COMPARE(std::abs(fx - dx), <, 1e-13);  // int phi_j x on both sides
      TEST_COMPARE(std::abs(fy - dy), <, 1e-13);
    }
    TEST_FLOATING_EQUALITY(total, 1.0, 1e-12);  // the slave square is covered
    contact::ContactSearchOptions o;
    o.searchRadius = 0.5;
    const auto m = contact::makeMortarMaster(slave.s, master.s, o);
    std::vector<int> nodes(25);
    for (int k = 0; k < 25; ++k) nodes[k] = k;
    const auto r = m->rows(master.x, nodes);
    TEST_EQUALITY(r.rows.size(), std::size_t(25));
    for (const auto& row : r.rows) TEST_FLOATING_EQUALITY(row.gap, 0.02, 1e-11);
  }
}

// The search along each slave facet's normal: the couplings are the same for any search radius
// that holds the gap, the (slave, master) pairs examined do not grow with the radius, a master
// farther along the normal than several facets is found, and one beyond the radius is not.
TEUCHOS_UNIT_TEST(Mortar, SearchAlongTheNormal) {
  for (double gap : {0.02, 0.4}) {
    Grid slave, master;
    addGrid(slave, 4, 1.0, 0.0, 0.0, 0.0, 0.0, true, false);  // facets of 0.25
    master.x = slave.x;
    addGrid(master, 28, 4.0, 0.3, 0.05, -0.02, gap, false, true);  // 0.14, beyond the slave
    const auto tight = contact::mortarCouplings(master.x, slave.s, master.s, gap + 0.05);
    TEST_EQUALITY(tight.byNode.size(), std::size_t(25));
    for (double radius : {1.0, 10.0}) {
      const auto wide = contact::mortarCouplings(master.x, slave.s, master.s, radius);
      TEST_EQUALITY(wide.candidatePairs, tight.candidatePairs);
      TEST_EQUALITY(wide.overlaps, tight.overlaps);
      TEST_EQUALITY(wide.byNode.size(), tight.byNode.size());
      for (const auto& [j, cj] : tight.byNode) {
        const auto& w = wide.byNode.at(j);
        TEST_EQUALITY(w.weight, cj.weight);  // bitwise: the same overlaps, in the same order
        TEST_EQUALITY(w.master.size(), cj.master.size());
        for (const auto& [k, m] : cj.master) TEST_EQUALITY(w.master.at(k), m);
      }
    }
    // Each slave facet (0.25 wide) examines a few dozen of the master's 0.14 triangles, not the
    // master's 1,568.
    TEST_COMPARE(tight.candidatePairs, <, 16 * 40);
    const auto beyond = contact::mortarCouplings(master.x, slave.s, master.s, 0.9 * gap);
    TEST_ASSERT(beyond.byNode.empty());
  }
}

// Matching 2D meshes: D is the identity times W_j and M couples each slave node to the master
// node opposite it only, so the rows are node-to-segment's (up to zero entries).
TEUCHOS_UNIT_TEST(Mortar, MatchingMeshesGiveNodeWiseRows) {
  std::vector<double> x;
  const int n = 5;
  for (int i = 0; i <= n; ++i) x.insert(x.end(), {double(i) / n, 0.0});
  for (int i = 0; i <= n; ++i) x.insert(x.end(), {double(i) / n, 0.05});
  MortarSurface slave{2, ElementType::Line2, {}}, master{2, ElementType::Line2, {}};
  for (int i = 0; i < n; ++i) {
    slave.facets.insert(slave.facets.end(), {i + 1, i});
    master.facets.insert(master.facets.end(), {n + 1 + i, n + 2 + i});
  }
  contact::ContactSearchOptions o;
  o.searchRadius = 0.2;
  const auto r = contact::makeMortarMaster(slave, master, o)->rows(x, {0, 1, 2, 3, 4, 5});
  TEST_EQUALITY(r.rows.size(), std::size_t(n + 1));
  for (const auto& row : r.rows) {
    TEST_FLOATING_EQUALITY(row.gap, 0.05, 1e-13);
    std::map<int, double> y;
    for (const auto& e : row.entries)
      if (e.component == 1) y[e.node] += e.coef;
    for (const auto& [node, coef] : y) {
      const double expected = node == row.slaveNode           ? 1.0
                              : node == row.slaveNode + n + 1 ? -1.0
                                                              : 0.0;
      TEST_COMPARE(std::abs(coef - expected), <, 1e-12);
    }
  }
}

// A rigid plane z = -h below a flat Quad9 (and a Tri6) surface whose outward normal is -z: every
// weighted gap is h, the rows hold the slave nodes only with the plane's normal, and the
// weights sum to the surface's area.
TEUCHOS_UNIT_TEST(Mortar, RigidObstacleWeightedGap) {
  for (ElementType t : {ElementType::Quad9, ElementType::Tri6}) {
    // One facet on the unit square at z = 0, corners clockwise seen from +z (normal -z).
    std::vector<double> x;
    MortarSurface s{3, t, {}};
    if (t == ElementType::Quad9) {
      x = {0, 0,   0, 0, 1, 0,   1, 1,   0, 1, 0,   0,   0, 0.5,
           0, 0.5, 1, 0, 1, 0.5, 0, 0.5, 0, 0, 0.5, 0.5, 0};
      s.facets = {0, 1, 2, 3, 4, 5, 6, 7, 8};
    } else {
      x = {0, 0, 0, 0, 1, 0, 1, 0, 0, 0, 0.5, 0, 0.5, 0.5, 0, 0.5, 0, 0};
      s.facets = {0, 1, 2, 3, 4, 5};
    }
    contact::RigidObstacle plane;
    plane.dim = 3;
    plane.point = {0.0, 0.0, -0.01};
    plane.normal = {0.0, 0.0, 1.0};
    contact::ContactSearchOptions o;
    o.searchRadius = 0.1;
    std::vector<int> nodes(s.facets);
    const auto r = contact::makeMortarObstacleMaster(s, plane, o)->rows(x, nodes);
    TEST_EQUALITY(r.rows.size(), s.facets.size());  // Tri6's midside nodes included
    double area = 0.0;
    for (const auto& row : r.rows) {
      TEST_FLOATING_EQUALITY(row.gap, 0.01, 1e-12);
      TEST_FLOATING_EQUALITY(row.normal[2], 1.0, 1e-14);
      area += row.weight;
      // Tri6: the modified quadratic shares, 2/15 of the facet at a corner and 1/5 midside.
      if (t == ElementType::Tri6)
        TEST_FLOATING_EQUALITY(row.weight, row.slaveNode < 3 ? 0.5 * 2.0 / 15.0 : 0.5 / 5.0, 1e-13);
    }
    TEST_FLOATING_EQUALITY(area, t == ElementType::Quad9 ? 1.0 : 0.5, 1e-13);
  }
}

TEUCHOS_UNIT_TEST(Mortar, BadInputIsNamed) {
  const std::vector<double> x = {0.0, 0.0, 1.0, 0.0};
  MortarSurface s{2, ElementType::Tri3, {0, 1}};
  TEST_THROW(contact::mortarCouplings(x, s, s, 1.0), std::invalid_argument);
  MortarSurface l{2, ElementType::Line2, {0, 7}};
  TEST_THROW(contact::mortarCouplings(x, l, l, 1.0), std::invalid_argument);
  MortarSurface ok{2, ElementType::Line2, {0, 1}};
  TEST_THROW(contact::mortarCouplings(x, ok, ok, 0.0), std::invalid_argument);
}

}  // namespace
