// Loading unstructured meshes through Gmsh: .geo files meshed at run time (orders 1 and 2,
// triangles and recombined quads) and stored .msh files, checked against what is exactly known
// about them: the counts of a transfinite (structured) rectangle, Euler's formula for the
// unstructured ones, the length of straight boundaries and the circle the curved one lies on.
// And every error path: missing and malformed files, unknown group names, unsupported and mixed
// element types, a mesh off the plane z = 0, bad options.
#include <Teuchos_UnitTestHarness.hpp>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "contact_ElasticContactProblem.hpp"
#include "contact_GmshMesh.hpp"
#include "plasticity_Elements.hpp"

namespace {

using contact::loadMesh;

const std::string kMeshDir = CONTACT_TEST_MESH_DIR;

std::string meshFile(const std::string& name) {
  return kMeshDir + "/" + name;
}

contact::MeshOptions opts(int order, bool quads, double sizeFactor = 1.0) {
  contact::MeshOptions o;
  o.order = order;
  o.quads = quads;
  o.sizeFactor = sizeFactor;
  return o;
}

double x(const contact::GmshMesh& m, int n) {
  return m.coords[2 * n];
}
double y(const contact::GmshMesh& m, int n) {
  return m.coords[2 * n + 1];
}

double edgeLength(const contact::GmshMesh& m, const contact::GmshBoundary& g, int i) {
  const int a = g.edges[i * g.nodesPerEdge], b = g.edges[i * g.nodesPerEdge + 1];
  return std::hypot(x(m, b) - x(m, a), y(m, b) - y(m, a));
}

double totalLength(const contact::GmshMesh& m, const contact::GmshBoundary& g) {
  double len = 0.0;
  for (int i = 0; i < g.numEdges(); ++i) len += edgeLength(m, g, i);
  return len;
}

// Largest distance of a midside node of a boundary from its edge's midpoint (0 for first order).
double maxMidsideOffset(const contact::GmshMesh& m, const contact::GmshBoundary& g) {
  double worst = 0.0;
  if (g.nodesPerEdge < 3) return worst;
  for (int i = 0; i < g.numEdges(); ++i) {
    const int a = g.edges[3 * i], b = g.edges[3 * i + 1], c = g.edges[3 * i + 2];
    worst = std::max(worst, std::hypot(x(m, c) - 0.5 * (x(m, a) + x(m, b)),
                                       y(m, c) - 0.5 * (y(m, a) + y(m, b))));
  }
  return worst;
}

// Signed area of element e's corner polygon (exact for straight-sided elements).
double cornerArea(const contact::GmshMesh& m, const contact::GmshBody& b, int e) {
  const int nc = contact::numCorners(b.type), npe = b.nodesPerElement();
  double a = 0.0;
  for (int k = 0; k < nc; ++k) {
    const int p = b.connectivity[e * npe + k], q = b.connectivity[e * npe + (k + 1) % nc];
    a += x(m, p) * y(m, q) - x(m, q) * y(m, p);
  }
  return 0.5 * a;
}

// Counts of a body's mesh computed from its connectivity alone.
struct Topology {
  int corners = 0;              // distinct corner nodes
  int others = 0;               // distinct non-corner nodes
  int edges = 0;                // distinct edges
  int boundaryEdges = 0;        // edges of one element only
  std::set<int> boundaryNodes;  // all nodes (midside included) on boundary edges
};

Topology topology(const contact::GmshBody& b) {
  const int nc = contact::numCorners(b.type), npe = b.nodesPerElement();
  std::set<int> corners, all;
  std::map<std::pair<int, int>, std::vector<int>> edges;  // end nodes -> all edge nodes, count
  std::map<std::pair<int, int>, int> count;
  for (int e = 0; e < b.numElements(); ++e) {
    const int* el = &b.connectivity[e * npe];
    for (int a = 0; a < npe; ++a) (a < nc ? corners : all).insert(el[a]);
    for (int k = 0; k < nc; ++k) {
      std::vector<int> nodes;
      for (int a : contact::elementEdgeNodes(b.type, k)) nodes.push_back(el[a]);
      const auto key = std::minmax(nodes[0], nodes[1]);
      edges[key] = nodes;
      ++count[key];
    }
  }
  Topology t;
  t.corners = static_cast<int>(corners.size());
  for (int n : corners) all.erase(n);
  t.others = static_cast<int>(all.size());
  t.edges = static_cast<int>(edges.size());
  for (const auto& [key, c] : count)
    if (c == 1) {
      ++t.boundaryEdges;
      t.boundaryNodes.insert(edges[key].begin(), edges[key].end());
    }
  return t;
}

std::set<int> nodesOf(const contact::GmshBoundary& g) {
  return std::set<int>(g.edges.begin(), g.edges.end());
}

// Every edge of the boundary is an edge of the element it is related to, with the same nodes
// (midside included).
bool edgesMatchElements(const contact::GmshMesh& m, const contact::GmshBoundary& g,
                        int expectedBody) {
  for (int i = 0; i < g.numEdges(); ++i) {
    if (g.edgeBody[i] != expectedBody || g.edgeElement[i] < 0) return false;
    const contact::GmshBody& b = m.bodies[g.edgeBody[i]];
    std::multiset<int> fromElement,
        fromEdge(g.edges.begin() + i * g.nodesPerEdge, g.edges.begin() + (i + 1) * g.nodesPerEdge);
    for (int a : contact::elementEdgeNodes(b.type, g.edgeLocalEdge[i]))
      fromElement.insert(b.connectivity[g.edgeElement[i] * b.nodesPerElement() + a]);
    if (fromElement != fromEdge) return false;
  }
  return true;
}

template <class F>
std::string errorOf(F&& f) {
  try {
    f();
  } catch (const std::exception& e) {
    return e.what();
  }
  return "";
}

bool contains(const std::string& s, const std::string& part) {
  return s.find(part) != std::string::npos;
}

// ---------------------------------------------------------------------------------------------

TEUCHOS_UNIT_TEST(GmshMesh, TransfiniteRectangleExactCounts) {
  for (int order : {1, 2})
    for (bool quads : {false, true}) {
      out << "order " << order << (quads ? " quads" : " triangles") << "\n";
      const contact::GmshMesh m = loadMesh(meshFile("rectangle.geo"), opts(order, quads));
      // 8 x 4 cells: (8+1)(4+1) corner nodes, (16+1)(8+1) with midside (and centre) nodes.
      TEST_EQUALITY(m.numNodes(), order == 1 ? 45 : 153);
      TEST_EQUALITY(m.coords.size(), 2 * m.gmshNodes.size());
      TEST_EQUALITY(m.bodies.size(), 1u);
      const contact::GmshBody& plate = m.body("plate");
      const contact::ElementType expected =
          quads ? (order == 1 ? contact::ElementType::Quad4 : contact::ElementType::Quad9)
                : (order == 1 ? contact::ElementType::Tri3 : contact::ElementType::Tri6);
      TEST_ASSERT(plate.type == expected);
      TEST_EQUALITY(plate.numElements(), quads ? 32 : 64);
      TEST_EQUALITY(plate.connectivity.size(),
                    static_cast<std::size_t>(plate.numElements() * plate.nodesPerElement()));

      double area = 0.0, minArea = 1e300;
      for (int e = 0; e < plate.numElements(); ++e) {
        area += cornerArea(m, plate, e);
        minArea = std::min(minArea, cornerArea(m, plate, e));
      }
      TEST_FLOATING_EQUALITY(area, 2.0, 1e-12);
      TEST_COMPARE(minArea, >, 0.0);  // counter-clockwise, as the curve loop

      TEST_EQUALITY(m.boundaries.size(), 4u);
      const std::map<std::string, std::pair<int, double>> sides = {
          {"bottom", {8, 2.0}}, {"right", {4, 1.0}}, {"top", {8, 2.0}}, {"left", {4, 1.0}}};
      for (const auto& [name, expect] : sides) {
        const contact::GmshBoundary& g = m.boundary(name);
        TEST_EQUALITY(g.nodesPerEdge, order + 1);
        TEST_EQUALITY(g.numEdges(), expect.first);
        TEST_EQUALITY(static_cast<int>(g.edges.size()), g.numEdges() * g.nodesPerEdge);
        TEST_FLOATING_EQUALITY(totalLength(m, g), expect.second, 1e-12);
        TEST_COMPARE(maxMidsideOffset(m, g), <, 1e-12);
        TEST_ASSERT(edgesMatchElements(m, g, 0));
      }
      // The four sides are the whole boundary of the plate.
      std::set<int> sideNodes;
      for (const contact::GmshBoundary& g : m.boundaries)
        sideNodes.insert(g.edges.begin(), g.edges.end());
      TEST_ASSERT(sideNodes == topology(plate).boundaryNodes);
      // Compact ids: every node is used and the Gmsh tags are increasing.
      std::set<int> used(plate.connectivity.begin(), plate.connectivity.end());
      TEST_EQUALITY(static_cast<int>(used.size()), m.numNodes());
      TEST_ASSERT(std::is_sorted(m.gmshNodes.begin(), m.gmshNodes.end()));
    }
}

TEUCHOS_UNIT_TEST(GmshMesh, TwoBodiesFirstOrderTriangles) {
  const contact::GmshMesh m = loadMesh(meshFile("cylinder_on_block.geo"), opts(1, false));
  TEST_EQUALITY(m.bodies.size(), 2u);
  TEST_EQUALITY(m.boundaries.size(), 5u);
  const int cyl = m.bodyIndex("cylinder"), blk = m.bodyIndex("block");
  TEST_ASSERT(cyl != blk);
  for (int b : {cyl, blk}) {
    const contact::GmshBody& body = m.bodies[b];
    TEST_ASSERT(body.type == contact::ElementType::Tri3);
    // Euler's formula for a triangulated disc: T = 2V - Vb - 2.
    const Topology t = topology(body);
    TEST_EQUALITY(body.numElements(), 2 * t.corners - static_cast<int>(t.boundaryNodes.size()) - 2);
    for (int e = 0; e < body.numElements(); ++e) TEST_COMPARE(cornerArea(m, body, e), >, 0.0);
  }
  // Plausible sizes for lc = 0.2 (cylinder, 0.1 at the contact point) and 0.4 (block).
  TEST_COMPARE(m.bodies[cyl].numElements(), >, 60);
  TEST_COMPARE(m.bodies[cyl].numElements(), <, 600);
  TEST_COMPARE(m.bodies[blk].numElements(), >, 30);
  TEST_COMPARE(m.bodies[blk].numElements(), <, 300);

  // The bodies only touch: no shared node.
  std::set<int> cylNodes(m.bodies[cyl].connectivity.begin(), m.bodies[cyl].connectivity.end());
  for (int n : m.bodies[blk].connectivity) TEST_ASSERT(cylNodes.count(n) == 0);

  // Straight boundaries have their exact lengths; the arcs' nodes lie on the circle.
  TEST_FLOATING_EQUALITY(totalLength(m, m.boundary("load")), 2.0, 1e-12);
  TEST_FLOATING_EQUALITY(totalLength(m, m.boundary("block_contact")), 4.0, 1e-12);
  TEST_FLOATING_EQUALITY(totalLength(m, m.boundary("fixed")), 4.0, 1e-12);
  TEST_FLOATING_EQUALITY(totalLength(m, m.boundary("block_sides")), 2.0, 1e-12);
  const contact::GmshBoundary& arc = m.boundary("cylinder_contact");
  double maxRadiusError = 0.0;
  for (int n : arc.edges)
    maxRadiusError = std::max(maxRadiusError, std::abs(std::hypot(x(m, n), y(m, n) - 1.0) - 1.0));
  TEST_COMPARE(maxRadiusError, <, 1e-12);
  const double chords = totalLength(m, arc);
  TEST_COMPARE(chords, <, M_PI);
  TEST_COMPARE(chords, >, M_PI * (1.0 - 0.2 * 0.2 / 24.0 * 1.01));  // chord error <= h^2/24

  // Each boundary's edges are edges of its body's elements, and together they are the body's
  // whole boundary.
  TEST_ASSERT(edgesMatchElements(m, arc, cyl));
  TEST_ASSERT(edgesMatchElements(m, m.boundary("load"), cyl));
  for (const char* name : {"block_contact", "fixed", "block_sides"})
    TEST_ASSERT(edgesMatchElements(m, m.boundary(name), blk));
  std::set<int> cylBoundary = nodesOf(arc), blkBoundary = nodesOf(m.boundary("fixed"));
  for (int n : nodesOf(m.boundary("load"))) cylBoundary.insert(n);
  for (const char* name : {"block_contact", "block_sides"})
    for (int n : nodesOf(m.boundary(name))) blkBoundary.insert(n);
  TEST_ASSERT(cylBoundary == topology(m.bodies[cyl]).boundaryNodes);
  TEST_ASSERT(blkBoundary == topology(m.bodies[blk]).boundaryNodes);
  TEST_EQUALITY(arc.numEdges() + m.boundary("load").numEdges(),
                topology(m.bodies[cyl]).boundaryEdges);
}

TEUCHOS_UNIT_TEST(GmshMesh, TwoBodiesSecondOrderAndQuads) {
  const contact::GmshMesh tri1 = loadMesh(meshFile("cylinder_on_block.geo"), opts(1, false));
  for (int order : {1, 2})
    for (bool quads : {false, true}) {
      if (order == 1 && !quads) continue;  // the previous test
      out << "order " << order << (quads ? " quads" : " triangles") << "\n";
      const contact::GmshMesh m = loadMesh(meshFile("cylinder_on_block.geo"), opts(order, quads));
      TEST_EQUALITY(m.bodies.size(), 2u);
      for (const contact::GmshBody& body : m.bodies) {
        const Topology t = topology(body);
        const int nb = t.boundaryEdges;  // = boundary corner nodes on a closed boundary
        const int nel = body.numElements();
        if (quads) {
          TEST_ASSERT(body.type ==
                      (order == 1 ? contact::ElementType::Quad4 : contact::ElementType::Quad9));
          TEST_EQUALITY(nel, t.corners - nb / 2 - 1);  // Euler for a quadrangulated disc
          TEST_EQUALITY(2 * t.edges, 4 * nel + nb);
          TEST_EQUALITY(t.others, order == 1 ? 0 : t.edges + nel);  // midside + centre nodes
        } else {
          TEST_ASSERT(body.type == contact::ElementType::Tri6);
          TEST_EQUALITY(nel, 2 * t.corners - nb - 2);
          TEST_EQUALITY(2 * t.edges, 3 * nel + nb);
          TEST_EQUALITY(t.others, t.edges);
          // Elevating the order does not change the first-order mesh.
          TEST_EQUALITY(nel, tri1.body(body.name).numElements());
        }
        for (int e = 0; e < nel; ++e) TEST_COMPARE(cornerArea(m, body, e), >, 0.0);
      }
      int total = 0;
      for (const contact::GmshBody& body : m.bodies) {
        const Topology t = topology(body);
        total += t.corners + t.others;
      }
      TEST_EQUALITY(m.numNodes(), total);  // bodies share no node; every node is used

      const int cyl = m.bodyIndex("cylinder"), blk = m.bodyIndex("block");
      for (const contact::GmshBoundary& g : m.boundaries) {
        TEST_EQUALITY(g.nodesPerEdge, order + 1);
        const bool onCylinder = g.name == "cylinder_contact" || g.name == "load";
        TEST_ASSERT(edgesMatchElements(m, g, onCylinder ? cyl : blk));
      }
      TEST_FLOATING_EQUALITY(totalLength(m, m.boundary("load")), 2.0, 1e-12);
      TEST_FLOATING_EQUALITY(totalLength(m, m.boundary("block_contact")), 4.0, 1e-12);
      TEST_COMPARE(maxMidsideOffset(m, m.boundary("block_contact")), <, 1e-12);
      // Second-order nodes of the arc are on the circle, not on the chords.
      const contact::GmshBoundary& arc = m.boundary("cylinder_contact");
      double maxRadiusError = 0.0;
      for (int n : arc.edges)
        maxRadiusError =
            std::max(maxRadiusError, std::abs(std::hypot(x(m, n), y(m, n) - 1.0) - 1.0));
      TEST_COMPARE(maxRadiusError, <, 1e-12);
      if (order == 2) TEST_COMPARE(maxMidsideOffset(m, arc), >, 1e-4);
    }
}

TEUCHOS_UNIT_TEST(GmshMesh, SizeFactorRefines) {
  const contact::GmshMesh coarse = loadMesh(meshFile("cylinder_on_block.geo"), opts(1, false));
  const contact::GmshMesh fine = loadMesh(meshFile("cylinder_on_block.geo"), opts(1, false, 0.5));
  // Halving h roughly quadruples the element count.
  for (const char* name : {"cylinder", "block"}) {
    const double ratio =
        static_cast<double>(fine.body(name).numElements()) / coarse.body(name).numElements();
    out << name << ": ratio " << ratio << "\n";
    TEST_COMPARE(ratio, >, 2.5);
    TEST_COMPARE(ratio, <, 6.0);
  }
  TEST_EQUALITY(fine.boundary("load").numEdges(), 2 * coarse.boundary("load").numEdges());
}

TEUCHOS_UNIT_TEST(GmshMesh, StoredMshFile) {
  // rectangle_quad9.msh: rectangle.geo meshed by Gmsh with quads, order 2 (MSH 4.1).
  const contact::GmshMesh m = loadMesh(meshFile("rectangle_quad9.msh"));
  TEST_EQUALITY(m.numNodes(), 153);
  TEST_ASSERT(m.body("plate").type == contact::ElementType::Quad9);
  TEST_EQUALITY(m.body("plate").numElements(), 32);
  TEST_EQUALITY(m.boundary("left").numEdges(), 4);
  TEST_EQUALITY(m.boundary("left").nodesPerEdge, 3);
  TEST_FLOATING_EQUALITY(totalLength(m, m.boundary("bottom")), 2.0, 1e-12);
  // A .msh is used as stored: the generation options do not apply.
  const contact::GmshMesh same = loadMesh(meshFile("rectangle_quad9.msh"), opts(1, false, 0.5));
  TEST_EQUALITY(same.numNodes(), 153);
  TEST_COMPARE_ARRAYS(same.body("plate").connectivity, m.body("plate").connectivity);
}

TEUCHOS_UNIT_TEST(GmshMesh, SelectedGroupsAndCompactNodes) {
  contact::MeshOptions o;
  o.bodies = {"cylinder"};
  o.boundaries = {"load"};
  const contact::GmshMesh m = loadMesh(meshFile("cylinder_on_block.geo"), o);
  TEST_EQUALITY(m.bodies.size(), 1u);
  TEST_EQUALITY(m.boundaries.size(), 1u);
  TEST_EQUALITY(m.bodies[0].name, "cylinder");
  TEST_EQUALITY(m.boundaries[0].name, "load");
  // Only the cylinder's nodes are kept, numbered 0..n-1.
  const std::set<int> used(m.bodies[0].connectivity.begin(), m.bodies[0].connectivity.end());
  TEST_EQUALITY(static_cast<int>(used.size()), m.numNodes());
  TEST_EQUALITY(*used.begin(), 0);
  TEST_EQUALITY(*used.rbegin(), m.numNodes() - 1);
  const contact::GmshMesh all = loadMesh(meshFile("cylinder_on_block.geo"));
  TEST_EQUALITY(m.bodies[0].numElements(), all.body("cylinder").numElements());
  TEST_COMPARE(m.numNodes(), <, all.numNodes());
  // The same physical coordinates element by element, under the two numberings.
  double maxDiff = 0.0;
  const contact::GmshBody &a = m.bodies[0], &b = all.body("cylinder");
  for (std::size_t i = 0; i < a.connectivity.size(); ++i)
    maxDiff = std::max({maxDiff, std::abs(x(m, a.connectivity[i]) - x(all, b.connectivity[i])),
                        std::abs(y(m, a.connectivity[i]) - y(all, b.connectivity[i]))});
  TEST_EQUALITY(maxDiff, 0.0);
}

TEUCHOS_UNIT_TEST(GmshMesh, MissingFile) {
  const std::string path = meshFile("does_not_exist.msh");
  const std::string msg = errorOf([&] { loadMesh(path); });
  out << msg << "\n";
  TEST_ASSERT(contains(msg, path));
  TEST_ASSERT(contains(msg, "cannot open"));
  TEST_THROW(loadMesh(path), std::runtime_error);
  TEST_THROW(loadMesh(meshFile("does_not_exist.geo")), std::runtime_error);
}

TEUCHOS_UNIT_TEST(GmshMesh, MalformedMsh) {
  // malformed.msh: rectangle_quad9.msh cut off inside its $Nodes section.
  const std::string path = meshFile("malformed.msh");
  TEST_THROW(loadMesh(path), std::runtime_error);
  const std::string msg = errorOf([&] { loadMesh(path); });
  out << msg << "\n";
  TEST_ASSERT(contains(msg, path));
  TEST_ASSERT(contains(msg, "Could not read nodes"));  // Gmsh's own message
  // A failed read leaves Gmsh usable for the next file.
  TEST_EQUALITY(loadMesh(meshFile("rectangle.geo")).numNodes(), 45);
}

TEUCHOS_UNIT_TEST(GmshMesh, MalformedGeo) {
  const std::string path = meshFile("malformed.geo");
  TEST_THROW(loadMesh(path), std::runtime_error);
  const std::string msg = errorOf([&] { loadMesh(path); });
  out << msg << "\n";
  TEST_ASSERT(contains(msg, path));
  TEST_ASSERT(contains(msg, "line 3") && contains(msg, "syntax error"));
  TEST_EQUALITY(loadMesh(meshFile("rectangle.geo")).numNodes(), 45);
}

TEUCHOS_UNIT_TEST(GmshMesh, UnknownGroupNameListsAvailable) {
  contact::MeshOptions o;
  o.bodies = {"cylinder", "cilinder"};
  TEST_THROW(loadMesh(meshFile("cylinder_on_block.geo"), o), std::invalid_argument);
  std::string msg = errorOf([&] { loadMesh(meshFile("cylinder_on_block.geo"), o); });
  out << msg << "\n";
  TEST_ASSERT(contains(msg, "cylinder_on_block.geo"));
  TEST_ASSERT(contains(msg, "\"cilinder\""));
  TEST_ASSERT(contains(msg, "\"cylinder\"") && contains(msg, "\"block\""));

  contact::MeshOptions ob;
  ob.boundaries = {"contact"};
  msg = errorOf([&] { loadMesh(meshFile("cylinder_on_block.geo"), ob); });
  out << msg << "\n";
  for (const char* name : {"cylinder_contact", "load", "block_contact", "fixed", "block_sides"})
    TEST_ASSERT(contains(msg, std::string("\"") + name + "\""));

  const contact::GmshMesh m = loadMesh(meshFile("rectangle.geo"));
  TEST_THROW(m.body("plat"), std::invalid_argument);
  msg = errorOf([&] { m.boundary("front"); });
  out << msg << "\n";
  TEST_ASSERT(contains(msg, "rectangle.geo") && contains(msg, "\"front\""));
  for (const char* name : {"bottom", "right", "top", "left"})
    TEST_ASSERT(contains(msg, std::string("\"") + name + "\""));
  msg = errorOf([&] { m.bodyIndex("plat"); });
  TEST_ASSERT(contains(msg, "\"plate\""));
}

TEUCHOS_UNIT_TEST(GmshMesh, UnsupportedAndMixedElementTypes) {
  // rectangle_quad8.msh: rectangle.geo as incomplete second-order quads (Gmsh type 16).
  std::string msg = errorOf([&] { loadMesh(meshFile("rectangle_quad8.msh")); });
  out << msg << "\n";
  TEST_ASSERT(contains(msg, "rectangle_quad8.msh"));
  TEST_ASSERT(contains(msg, "type 16"));
  TEST_ASSERT(contains(msg, "not supported"));
  TEST_THROW(loadMesh(meshFile("rectangle_quad8.msh")), std::runtime_error);

  msg = errorOf([&] { loadMesh(meshFile("mixed_types.geo")); });
  out << msg << "\n";
  TEST_ASSERT(contains(msg, "mixed_types.geo"));
  TEST_ASSERT(contains(msg, "\"mixed\""));
  TEST_ASSERT(contains(msg, "mixes element types"));
  // With every surface recombined the same file is a valid all-quad body.
  const contact::GmshMesh q = loadMesh(meshFile("mixed_types.geo"), opts(1, true));
  TEST_ASSERT(q.body("mixed").type == contact::ElementType::Quad4);
  TEST_EQUALITY(q.body("mixed").numElements(), 8);
}

TEUCHOS_UNIT_TEST(GmshMesh, OffPlaneMesh) {
  const std::string msg = errorOf([&] { loadMesh(meshFile("off_plane.geo")); });
  out << msg << "\n";
  TEST_ASSERT(contains(msg, "off_plane.geo"));
  TEST_ASSERT(contains(msg, "z = 1"));
  TEST_THROW(loadMesh(meshFile("off_plane.geo")), std::runtime_error);
}

TEUCHOS_UNIT_TEST(GmshMesh, InvalidOptionsAndFileType) {
  TEST_THROW(loadMesh(meshFile("rectangle.geo"), opts(3, false)), std::invalid_argument);
  TEST_THROW(loadMesh(meshFile("rectangle.geo"), opts(1, false, 0.0)), std::invalid_argument);
  TEST_THROW(loadMesh(meshFile("rectangle.geo"), opts(1, false, -1.0)), std::invalid_argument);
  const std::string msg = errorOf([&] { loadMesh(meshFile("rectangle.txt")); });
  TEST_ASSERT(contains(msg, "rectangle.txt") && contains(msg, "unknown mesh file type"));
  TEST_THROW(loadMesh(meshFile("rectangle.txt")), std::invalid_argument);
}

}  // namespace

namespace {

// A clockwise curve loop gives clockwise elements in Gmsh; the reader renumbers them
// counter-clockwise (corners and, for quadratic elements, the edge and centre nodes), so that
// every element has a positive Jacobian at every node of the reference element.
TEUCHOS_UNIT_TEST(GmshMesh, ClockwiseSurfaceIsReoriented) {
  for (int order : {1, 2})
    for (bool quads : {false, true}) {
      const contact::GmshMesh m = loadMesh(meshFile("clockwise_square.geo"), opts(order, quads));
      const contact::GmshBody& b = m.body("square");
      TEST_EQUALITY(b.reoriented, b.numElements());  // every element, and counted
      const plasticity::ElementMesh em{contact::checkedBodyType(b.type), m.coords, b.connectivity};
      // assembleStiffness rejects an element with a non-positive Jacobian, naming it.
      TEST_NOTHROW(plasticity::assembleStiffness(em, plasticity::ElasticLaw(1.0, 0.3)));
      const int npe = b.nodesPerElement(), corners = (npe == 3 || npe == 6) ? 3 : 4;
      double area = 0.0;
      for (int e = 0; e < b.numElements(); ++e) {
        const int* el = &b.connectivity[static_cast<std::size_t>(e) * npe];
        double twice = 0.0;
        for (int k = 0; k < corners; ++k) {
          const int p = el[k], q = el[(k + 1) % corners];
          twice += m.coords[2 * p] * m.coords[2 * q + 1] - m.coords[2 * q] * m.coords[2 * p + 1];
        }
        TEST_COMPARE(twice, >, 0.0);
        area += 0.5 * twice;
      }
      out << "order " << order << (quads ? " quads" : " triangles") << ": " << b.numElements()
          << " elements, area " << area << "\n";
      TEST_FLOATING_EQUALITY(area, 1.0, 1e-12);
    }
}

// A .msh file with one clockwise triangle (tag 12) of two: reoriented and counted; with a
// triangle whose corners are collinear (tag 17): an error naming the file and the Gmsh tag.
TEUCHOS_UNIT_TEST(GmshMesh, ReversedAndDegenerateElementsOfAMshFile) {
  const contact::GmshMesh m = loadMesh(meshFile("reversed_triangles.msh"));
  TEST_EQUALITY(m.body("plate").reoriented, 1);
  TEST_EQUALITY(m.body("plate").numElements(), 2);
  const std::string path = meshFile("degenerate_triangle.msh");
  const std::string msg = errorOf([&] { loadMesh(path); });
  out << msg << "\n";
  TEST_ASSERT(contains(msg, path));
  TEST_ASSERT(contains(msg, "triangle element 17 (Gmsh element tag) is degenerate"));
  TEST_THROW(loadMesh(path), std::runtime_error);
}

}  // namespace
