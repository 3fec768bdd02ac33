// Decomposition of unstructured bodies into subdomains: METIS parts split into edge-connected
// components. Checked with hand-made partitions whose components are known (including two
// pieces of one part that touch at a single node, which must be torn apart), and on meshed
// bodies for the invariants the tearing relies on: every element in exactly one subdomain,
// each subdomain edge-connected, local numbering consistent with the untorn mesh.
#include <Teuchos_UnitTestHarness.hpp>

#include <algorithm>
#include <array>
#include <map>
#include <numeric>
#include <set>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "contact_GmshMesh.hpp"
#include "contact_Partition.hpp"

namespace {

const std::string kMeshDir = CONTACT_TEST_MESH_DIR;

// An nx x ny grid of unit quads, elements row by row (e = i + nx*j), counter-clockwise.
contact::GmshMesh quadGrid(int nx, int ny) {
  contact::GmshMesh m;
  m.source = "quadGrid";
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i) {
      m.coords.push_back(i);
      m.coords.push_back(j);
      m.gmshNodes.push_back(m.gmshNodes.size() + 1);
    }
  contact::GmshBody b;
  b.name = "grid";
  b.type = contact::ElementType::Quad4;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const int n0 = i + (nx + 1) * j;
      for (int n : {n0, n0 + 1, n0 + nx + 2, n0 + nx + 1}) b.connectivity.push_back(n);
      b.gmshTags.push_back(b.gmshTags.size() + 1);
    }
  m.bodies.push_back(b);
  return m;
}

// Edge-connectedness of a set of elements given by local connectivity, checked independently of
// the library: union-find over elements sharing a pair of consecutive corners.
int countEdgeComponents(contact::ElementType type, const std::vector<int>& conn) {
  const int npe = contact::numNodes(type), nc = contact::numCorners(type);
  const int ne = static_cast<int>(conn.size()) / npe;
  std::vector<int> parent(ne);
  std::iota(parent.begin(), parent.end(), 0);
  auto find = [&](int a) {
    while (parent[a] != a) a = parent[a] = parent[parent[a]];
    return a;
  };
  std::map<std::pair<int, int>, int> firstWithEdge;
  for (int e = 0; e < ne; ++e)
    for (int k = 0; k < nc; ++k) {
      const auto key = std::minmax(conn[e * npe + k], conn[e * npe + (k + 1) % nc]);
      auto [it, inserted] = firstWithEdge.emplace(key, e);
      if (!inserted) parent[find(e)] = find(it->second);
    }
  int roots = 0;
  for (int e = 0; e < ne; ++e) roots += find(e) == e;
  return roots;
}

// The invariants every decomposition must satisfy; returns the number of violations.
int checkDecomposition(Teuchos::FancyOStream& out, const contact::GmshMesh& mesh,
                       const contact::GmshBody& body, const contact::BodyPartition& p) {
  int bad = 0;
  auto fail = [&](const std::string& what) {
    if (bad++ < 10) out << "violation: " << what << "\n";
  };
  const int npe = body.nodesPerElement();
  std::vector<int> owner(body.numElements(), -1);
  for (int s = 0; s < p.numSubdomains(); ++s) {
    const contact::UnstructuredSubdomain& sd = p.subdomains[s];
    if (sd.id != s) fail("subdomain ids are not consecutive");
    if (sd.type != body.type) fail("element type");
    if (sd.numElements() == 0) fail("empty subdomain");
    if (!std::is_sorted(sd.elements.begin(), sd.elements.end())) fail("elements not increasing");
    if (static_cast<int>(sd.connectivity.size()) != sd.numElements() * npe) fail("connectivity");
    if (static_cast<int>(sd.coords.size()) != 2 * sd.numNodes()) fail("coords size");
    if (std::adjacent_find(sd.globalNode.begin(), sd.globalNode.end(),
                           std::greater_equal<long long>()) != sd.globalNode.end())
      fail("globalNode not strictly increasing");
    for (int e : sd.elements) {
      if (owner[e] >= 0) fail("element " + std::to_string(e) + " in two subdomains");
      owner[e] = s;
    }
    // Local element nodes map back to the body's nodes, coordinates included.
    for (int i = 0; i < sd.numElements(); ++i)
      for (int a = 0; a < npe; ++a) {
        const int local = sd.connectivity[i * npe + a];
        const long long g = sd.globalNode[local];
        if (g != body.connectivity[sd.elements[i] * npe + a]) fail("local -> global node");
        if (sd.coords[2 * local] != mesh.coords[2 * g] ||
            sd.coords[2 * local + 1] != mesh.coords[2 * g + 1])
          fail("coordinates");
      }
    std::set<int> used(sd.connectivity.begin(), sd.connectivity.end());
    if (static_cast<int>(used.size()) != sd.numNodes()) fail("unused local node");
    if (countEdgeComponents(sd.type, sd.connectivity) != 1)
      fail("subdomain " + std::to_string(s) + " is not edge-connected");
  }
  for (int e = 0; e < body.numElements(); ++e)
    if (owner[e] < 0) fail("element " + std::to_string(e) + " in no subdomain");
  if (p.numSubdomains() != p.numParts - p.emptyParts + p.extraSubdomains)
    fail("subdomain count != parts - empty + extra");
  return bad;
}

// ---------------------------------------------------------------------------------------------

TEUCHOS_UNIT_TEST(Partition, CraftedDisconnectedPartsAreSplit) {
  // 3 x 3 grid, elements     6 7 8      parts   1 0 2
  //                          3 4 5              0 2 2
  //                          0 1 2              0 2 1
  // Part 0 = {0, 3} + {7}: 7 touches 3 only at the node (1, 2), which does not connect them
  // rigidly. Part 1 = {2} + {6}: apart. Part 2 = {1, 4, 5, 8}: connected through edges.
  const contact::GmshMesh m = quadGrid(3, 3);
  const std::vector<int> part = {0, 2, 1, 0, 2, 2, 1, 0, 2};
  const contact::BodyPartition p = contact::splitIntoSubdomains(m, m.bodies[0], part, 3, 10);
  TEST_EQUALITY(p.numParts, 3);
  TEST_EQUALITY(p.emptyParts, 0);
  TEST_EQUALITY(p.splitParts, 2);
  TEST_EQUALITY(p.extraSubdomains, 2);
  TEST_EQUALITY(p.numSubdomains(), 5);
  const std::vector<std::vector<int>> elements = {{0, 3}, {7}, {2}, {6}, {1, 4, 5, 8}};
  const std::vector<int> parts = {0, 0, 1, 1, 2};
  for (int s = 0; s < std::min(p.numSubdomains(), 5); ++s) {
    TEST_COMPARE_ARRAYS(p.subdomains[s].elements, elements[s]);
    TEST_EQUALITY(p.subdomains[s].part, parts[s]);
    TEST_EQUALITY(p.subdomains[s].id, 10 + s);
  }
  // The node at (1, 2) (untorn id 9) has a copy in both pieces of part 0.
  const std::vector<long long> lower = {0, 1, 4, 5, 8, 9}, upper = {9, 10, 13, 14};
  TEST_COMPARE_ARRAYS(p.subdomains[0].globalNode, lower);
  TEST_COMPARE_ARRAYS(p.subdomains[1].globalNode, upper);
  // Local connectivity of element 7 ((1,2)-(2,2)-(2,3)-(1,3)) and its coordinates.
  const std::vector<int> conn7 = {0, 1, 3, 2};
  TEST_COMPARE_ARRAYS(p.subdomains[1].connectivity, conn7);
  const std::vector<double> coords7 = {1, 2, 2, 2, 1, 3, 2, 3};
  TEST_COMPARE_ARRAYS(p.subdomains[1].coords, coords7);

  // The library's invariants checker agrees, and ids restart at 0 without firstId.
  const contact::BodyPartition p0 = contact::splitIntoSubdomains(m, m.bodies[0], part, 3);
  TEST_EQUALITY(checkDecomposition(out, m, m.bodies[0], p0), 0);
  // Whereas keeping part 0 whole would have been a node-connected, edge-disconnected subdomain.
  std::vector<int> part0Conn;
  for (int e : {0, 3, 7})
    for (int a = 0; a < 4; ++a) part0Conn.push_back(m.bodies[0].connectivity[4 * e + a]);
  TEST_EQUALITY(countEdgeComponents(contact::ElementType::Quad4, part0Conn), 2);
}

TEUCHOS_UNIT_TEST(Partition, CraftedTrianglesTouchingAtAVertex) {
  // A bow tie: triangles (0,1,2) and (2,3,4) share only node 2; a third triangle (4,5,3) shares
  // the edge 3-4 with the second. One part -> {0} and {1, 2}; an empty part 1 gets no subdomain.
  contact::GmshMesh m;
  m.source = "bowtie";
  m.coords = {0, 0, 1, 0, 0.5, 1, 1, 2, 0, 2, 1, 3};
  m.gmshNodes = {1, 2, 3, 4, 5, 6};
  contact::GmshBody b;
  b.name = "bowtie";
  b.type = contact::ElementType::Tri3;
  b.connectivity = {0, 1, 2, 2, 3, 4, 4, 3, 5};
  b.gmshTags = {1, 2, 3};
  m.bodies.push_back(b);
  const contact::BodyPartition p = contact::splitIntoSubdomains(m, b, {0, 0, 0}, 2);
  TEST_EQUALITY(p.numSubdomains(), 2);
  TEST_EQUALITY(p.emptyParts, 1);
  TEST_EQUALITY(p.splitParts, 1);
  TEST_EQUALITY(p.extraSubdomains, 1);
  if (p.numSubdomains() == 2) {
    TEST_COMPARE_ARRAYS(p.subdomains[0].elements, std::vector<int>({0}));
    TEST_COMPARE_ARRAYS(p.subdomains[1].elements, std::vector<int>({1, 2}));
    TEST_COMPARE_ARRAYS(p.subdomains[1].globalNode, std::vector<long long>({2, 3, 4, 5}));
  }
  TEST_EQUALITY(checkDecomposition(out, m, b, p), 0);
}

TEUCHOS_UNIT_TEST(Partition, ComponentsWithinParts) {
  const contact::GmshMesh m = quadGrid(3, 3);
  const contact::DualGraph g = contact::edgeDualGraph(m.bodies[0]);
  TEST_EQUALITY(g.numElements(), 9);
  // Centre element has four edge neighbours; corners two; no diagonal (node-only) neighbours.
  TEST_COMPARE_ARRAYS(
      std::vector<int>(g.neighbors.begin() + g.offsets[4], g.neighbors.begin() + g.offsets[5]),
      std::vector<int>({1, 3, 5, 7}));
  TEST_COMPARE_ARRAYS(
      std::vector<int>(g.neighbors.begin() + g.offsets[0], g.neighbors.begin() + g.offsets[1]),
      std::vector<int>({1, 3}));
  // Checkerboard: every element its own component within its part.
  const std::vector<int> part = {0, 1, 0, 1, 0, 1, 0, 1, 0};
  const std::vector<int> expected = {0, 0, 1, 1, 2, 2, 3, 3, 4};
  TEST_COMPARE_ARRAYS(contact::componentsWithinParts(g, part), expected);
  TEST_THROW(contact::componentsWithinParts(g, std::vector<int>(8, 0)), std::invalid_argument);
}

TEUCHOS_UNIT_TEST(Partition, MeshedBodiesMetis) {
  for (int order : {1, 2})
    for (bool quads : {false, true}) {
      contact::MeshOptions o;
      o.order = order;
      o.quads = quads;
      const contact::GmshMesh m = contact::loadMesh(kMeshDir + "/cylinder_on_block.geo", o);
      for (const contact::GmshBody& body : m.bodies)
        for (int n : {1, 2, 3, 4, 7, 16}) {
          const contact::BodyPartition p = contact::partitionBody(m, body, n);
          out << "order " << order << (quads ? " quads " : " triangles ") << body.name << " N " << n
              << ": " << p.numSubdomains() << " subdomains (" << p.splitParts << " parts split, "
              << p.emptyParts << " empty)\n";
          TEST_EQUALITY(p.numParts, n);
          TEST_EQUALITY(p.emptyParts, 0);
          TEST_EQUALITY(checkDecomposition(out, m, body, p), 0);
          TEST_EQUALITY(p.numSubdomains(), n + p.extraSubdomains);
          // The bodies are connected, so METIS is asked for contiguous parts: no splits.
          TEST_EQUALITY(p.extraSubdomains, 0);
          const std::vector<int> part = contact::partitionElements(body, n);
          std::set<int> parts(part.begin(), part.end());
          TEST_EQUALITY(static_cast<int>(parts.size()), n);
          // Deterministic: the same parts again (as on every other rank).
          TEST_COMPARE_ARRAYS(contact::partitionElements(body, n), part);
          if (n == 1) {
            TEST_EQUALITY(p.numSubdomains(), 1);
            TEST_EQUALITY(p.subdomains[0].numElements(), body.numElements());
          }
        }
    }
}

TEUCHOS_UNIT_TEST(Partition, BoundaryNodesOfWholeBody) {
  // With one subdomain its boundary nodes are exactly the nodes of the body's boundary groups,
  // midside nodes included.
  for (int order : {1, 2}) {
    contact::MeshOptions o;
    o.order = order;
    const contact::GmshMesh m = contact::loadMesh(kMeshDir + "/cylinder_on_block.geo", o);
    const contact::BodyPartition p = contact::partitionBody(m, m.body("cylinder"), 1);
    std::set<long long> expected;
    for (const char* name : {"cylinder_contact", "load"})
      for (int n : m.boundary(name).edges) expected.insert(n);
    std::set<long long> got;
    for (int local : p.subdomains[0].boundaryNodes()) got.insert(p.subdomains[0].globalNode[local]);
    TEST_ASSERT(got == expected);
    TEST_EQUALITY(got.size(), expected.size());
  }
  // Interior subdomain boundaries count too: a 2 x 1 grid cut in two.
  const contact::GmshMesh g = quadGrid(2, 1);
  const contact::BodyPartition p = contact::splitIntoSubdomains(g, g.bodies[0], {0, 1}, 2);
  TEST_EQUALITY(p.subdomains[0].boundaryNodes().size(), 4u);
}

TEUCHOS_UNIT_TEST(Partition, InvalidInput) {
  const contact::GmshMesh m = quadGrid(2, 2);
  const contact::GmshBody& b = m.bodies[0];
  TEST_THROW(contact::partitionElements(b, 0), std::invalid_argument);
  TEST_THROW(contact::partitionElements(b, 5), std::invalid_argument);
  TEST_THROW(contact::splitIntoSubdomains(m, b, {0, 0, 0}, 1), std::invalid_argument);
  TEST_THROW(contact::splitIntoSubdomains(m, b, {0, 0, 0, 2}, 2), std::invalid_argument);
  TEST_THROW(contact::splitIntoSubdomains(m, b, {0, 0, 0, -1}, 2), std::invalid_argument);
}

TEUCHOS_UNIT_TEST(Partition, TinyBodiesGetNoEmptyPart) {
  // One element per part: METIS alone leaves parts of the 2 x 2 grid empty.
  for (auto [nx, ny] : {std::pair<int, int>{2, 2}, {3, 1}, {3, 3}}) {
    const contact::GmshMesh m = quadGrid(nx, ny);
    const int n = nx * ny;
    const std::vector<int> part = contact::partitionElements(m.bodies[0], n);
    TEST_EQUALITY(static_cast<int>(std::set<int>(part.begin(), part.end()).size()), n);
    const contact::BodyPartition p = contact::partitionBody(m, m.bodies[0], n);
    TEST_EQUALITY(p.numSubdomains(), n);
    TEST_EQUALITY(p.emptyParts, 0);
    TEST_EQUALITY(checkDecomposition(out, m, m.bodies[0], p), 0);
  }
}

TEUCHOS_UNIT_TEST(Partition, BodyOfSeparatePieces) {
  // One body, two 4 x 4 blocks joined by nothing: a 9 x 4 grid without its middle column.
  contact::GmshMesh m = quadGrid(9, 4);
  contact::GmshBody& b = m.bodies[0];
  contact::GmshBody pieces = b;
  pieces.connectivity.clear();
  pieces.gmshTags.clear();
  for (int e = 0; e < b.numElements(); ++e) {
    if (e % 9 == 4) continue;
    pieces.connectivity.insert(pieces.connectivity.end(), b.connectivity.begin() + 4 * e,
                               b.connectivity.begin() + 4 * e + 4);
    pieces.gmshTags.push_back(b.gmshTags[e]);
  }
  for (int n : {1, 2, 3, 5}) {
    const contact::BodyPartition p = contact::partitionBody(m, pieces, n);
    out << "N " << n << ": " << p.numSubdomains() << " subdomains\n";
    TEST_EQUALITY(checkDecomposition(out, m, pieces, p), 0);
    TEST_EQUALITY(p.numSubdomains(), n + p.extraSubdomains);
    TEST_COMPARE(p.numSubdomains(), >=, 2);
    if (n == 1) {
      TEST_EQUALITY(p.splitParts, 1);
      TEST_EQUALITY(p.extraSubdomains, 1);
    }
  }
}

}  // namespace

namespace {

// Unit Hex8 cubes at the given integer offsets (Gmsh order: bottom face counter-clockwise seen
// from above, then the top face), nodes shared where cubes touch.
contact::GmshMesh hexCubes(const std::vector<std::array<int, 3>>& offsets) {
  contact::GmshMesh m;
  m.source = "hexCubes";
  m.dim = 3;
  contact::GmshBody b;
  b.name = "cubes";
  b.type = contact::ElementType::Hex8;
  std::map<std::array<int, 3>, int> id;
  const int corner[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                            {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  for (const auto& o : offsets) {
    for (const auto& c : corner) {
      const std::array<int, 3> p{o[0] + c[0], o[1] + c[1], o[2] + c[2]};
      auto [it, added] = id.insert({p, static_cast<int>(id.size())});
      if (added) {
        for (int v : p) m.coords.push_back(v);
        m.gmshNodes.push_back(m.gmshNodes.size() + 1);
      }
      b.connectivity.push_back(it->second);
    }
    b.gmshTags.push_back(b.gmshTags.size() + 1);
  }
  m.bodies.push_back(b);
  return m;
}

}  // namespace

// 3D: elements are neighbours through a shared face only. Two cubes sharing a face are one
// subdomain, all of whose nodes are on its boundary; cubes sharing just an edge or a vertex can
// rotate about it, so one part of them becomes separate subdomains.
TEUCHOS_UNIT_TEST(Partition, HexahedraConnectedThroughFacesOnly) {
  const auto faceShared = hexCubes({{0, 0, 0}, {1, 0, 0}});
  const auto one = contact::splitIntoSubdomains(faceShared, faceShared.bodies[0], {0, 0}, 1);
  TEST_EQUALITY(one.numSubdomains(), 1);
  TEST_EQUALITY(static_cast<int>(one.subdomains[0].boundaryNodes().size()), 12);
  TEST_EQUALITY(static_cast<int>(one.subdomains[0].coords.size()), 3 * 12);

  for (const auto& touching : {std::vector<std::array<int, 3>>{{0, 0, 0}, {1, 1, 0}},     // edge
                               std::vector<std::array<int, 3>>{{0, 0, 0}, {1, 1, 1}}}) {  // vertex
    const auto mesh = hexCubes(touching);
    const auto g = contact::edgeDualGraph(mesh.bodies[0]);
    TEST_EQUALITY(g.offsets[2], 0);  // no neighbours
    const auto split = contact::splitIntoSubdomains(mesh, mesh.bodies[0], {0, 0}, 1);
    TEST_EQUALITY(split.numSubdomains(), 2);
    TEST_EQUALITY(split.extraSubdomains, 1);
  }

  // A 3 x 3 x 3 block of cubes: its 4^3 nodes but the 2^3 inner ones are on its surface.
  std::vector<std::array<int, 3>> block;
  for (int k = 0; k < 3; ++k)
    for (int j = 0; j < 3; ++j)
      for (int i = 0; i < 3; ++i) block.push_back({i, j, k});
  const auto big = hexCubes(block);
  const auto whole = contact::splitIntoSubdomains(big, big.bodies[0], std::vector<int>(27, 0), 1);
  TEST_EQUALITY(whole.numSubdomains(), 1);
  TEST_EQUALITY(whole.subdomains[0].numNodes(), 64);
  TEST_EQUALITY(static_cast<int>(whole.subdomains[0].boundaryNodes().size()), 64 - 8);
}

// Coordinate bisection: a 6 x 4 x 2 block of unit cubes (elements shuffled, so that the cut does
// not follow the element order) into 12 parts gives 12 boxes of 4 cubes (each part's cubes fill
// the box their extent spans). 5 parts (not a power of two) get 9 or 10 elements each, each part
// one facet-connected subdomain (none split, every element in one). The same call gives the same
// parts; 0 parts, or more parts than elements, are errors. A 2D grid gives squares.
TEUCHOS_UNIT_TEST(Partition, CoordinateBisectionCutsABlockIntoBoxes) {
  std::vector<std::array<int, 3>> offsets;
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < 4; ++j)
      for (int i = 0; i < 6; ++i) offsets.push_back({i, j, k});
  std::vector<std::array<int, 3>> shuffled;
  for (std::size_t e = 0; e < offsets.size(); ++e) shuffled.push_back(offsets[(7 * e) % 48]);
  const contact::GmshMesh m = hexCubes(shuffled);
  const contact::GmshBody& b = m.bodies[0];
  const std::vector<int> part = contact::bisectCoordinates(m, b, 12);
  std::map<int, std::vector<std::array<int, 3>>> cubesOf;
  for (std::size_t e = 0; e < part.size(); ++e) cubesOf[part[e]].push_back(shuffled[e]);
  TEST_EQUALITY(cubesOf.size(), 12u);
  for (const auto& [p, cubes] : cubesOf) {
    std::array<int, 3> lo{99, 99, 99}, hi{-1, -1, -1};
    for (const auto& c : cubes)
      for (int d = 0; d < 3; ++d) {
        lo[d] = std::min(lo[d], c[d]);
        hi[d] = std::max(hi[d], c[d]);
      }
    out << "part " << p << ": " << cubes.size() << " cubes, extent " << hi[0] - lo[0] << " x "
        << hi[1] - lo[1] << " x " << hi[2] - lo[2] << "\n";
    TEST_EQUALITY(cubes.size(), 4u);
    TEST_EQUALITY(
        static_cast<std::size_t>((hi[0] - lo[0] + 1) * (hi[1] - lo[1] + 1) * (hi[2] - lo[2] + 1)),
        cubes.size());
  }
  TEST_ASSERT(contact::bisectCoordinates(m, b, 12) == part);

  const std::vector<int> five = contact::bisectCoordinates(m, b, 5);
  std::map<int, int> sizes;
  for (int p : five) ++sizes[p];
  TEST_EQUALITY(sizes.size(), 5u);
  for (const auto& [p, n] : sizes) TEST_ASSERT(n == 9 || n == 10);
  const contact::BodyPartition bp =
      contact::partitionBody(m, b, 5, 0, contact::Partitioner::CoordinateBisection);
  TEST_EQUALITY(bp.numSubdomains(), 5);
  TEST_EQUALITY(bp.splitParts, 0);
  std::vector<int> owners(b.numElements(), 0);
  for (const auto& sd : bp.subdomains)
    for (int e : sd.elements) ++owners[e];
  TEST_ASSERT(std::all_of(owners.begin(), owners.end(), [](int n) { return n == 1; }));

  TEST_THROW(contact::bisectCoordinates(m, b, 0), std::invalid_argument);
  TEST_THROW(contact::bisectCoordinates(m, b, 49), std::invalid_argument);

  // 2D: an 8 x 4 grid of quadrilaterals into 8 parts, squares of 2 x 2 (the element at (i, j)
  // is i + 8 j), each one subdomain.
  const contact::GmshMesh g = quadGrid(8, 4);
  const std::vector<int> squares = contact::bisectCoordinates(g, g.bodies[0], 8);
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 8; ++i) {
      const int e = i + 8 * j, corner = (i / 2) * 2 + 8 * ((j / 2) * 2);
      TEST_EQUALITY(squares[e], squares[corner]);
    }
  TEST_EQUALITY(std::set<int>(squares.begin(), squares.end()).size(), 8u);
  const contact::BodyPartition gp =
      contact::partitionBody(g, g.bodies[0], 8, 0, contact::Partitioner::CoordinateBisection);
  TEST_EQUALITY(gp.numSubdomains(), 8);
  TEST_EQUALITY(checkDecomposition(out, g, g.bodies[0], gp), 0);
}
