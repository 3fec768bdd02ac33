// The two cylinders extruded to a slab (examples/cylinders_3d.geo, Hex8 with quadrilateral
// contact faces) against the 2D quadrilateral mesh of examples/two_cylinders.geo: the extruded
// mesh repeats the 2D mesh on every node plane, and the node-to-face rows of every slave node are
// the 2D node-to-segment rows of its in-plane node (the same gap, kind and in-plane normal, the
// master coefficients on the slave's own node plane summing to the 2D ones). That is what makes
// the 3D slab with symmetry end planes the 2D plane-strain problem, node row by node row.
#include <Teuchos_UnitTestHarness.hpp>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "contact_ContactMaster.hpp"
#include "contact_GmshMesh.hpp"

namespace {

const std::string kExamples = CONTACT_TEST_EXAMPLES_DIR;
// The slab of cylinders_3d.geo: thickness and layers.
const double kThickness = 0.05;
const int kLayers = 2;

// A node by its body and in-plane position: the bodies touch at the origin with a node each.
using Key = std::tuple<int, double, double>;

std::vector<int> bodyOfNodes(const contact::GmshMesh& mesh) {
  std::vector<int> body(mesh.numNodes(), -1);
  for (std::size_t b = 0; b < mesh.bodies.size(); ++b)
    for (int n : mesh.bodies[b].connectivity) body[n] = static_cast<int>(b);
  return body;
}

struct Meshes {
  contact::GmshMesh flat, slab;
  std::vector<int> flatOf;  // the 2D node at each 3D node's (x, y)
  std::vector<int> plane;   // each 3D node's node plane, 0..kLayers
};

// Both meshes at size factor 2 (the tests' coarse mesh); every 3D node mapped to the 2D node at
// its (x, y) in the same body, which must exist and be exact (extrusion copies the coordinates).
Meshes loadBoth(Teuchos::FancyOStream& out, bool& success) {
  Meshes m;
  contact::MeshOptions o2;
  o2.quads = true;
  o2.sizeFactor = 2.0;
  m.flat = contact::loadMesh(kExamples + "/two_cylinders.geo", o2);
  contact::MeshOptions o3;
  o3.sizeFactor = 2.0;
  m.slab = contact::loadMesh(kExamples + "/cylinders_3d.geo", o3);
  const std::vector<int> body2 = bodyOfNodes(m.flat), body3 = bodyOfNodes(m.slab);
  std::map<Key, int> byXy;
  for (int n = 0; n < m.flat.numNodes(); ++n)
    byXy[{body2[n], m.flat.coords[2 * n], m.flat.coords[2 * n + 1]}] = n;
  for (int n = 0; n < m.slab.numNodes(); ++n) {
    const double* x = &m.slab.coords[3 * n];
    const auto it = byXy.find({body3[n], x[0], x[1]});
    m.flatOf.push_back(it == byXy.end() ? -1 : it->second);
    const double k = x[2] / kThickness * kLayers;
    m.plane.push_back(static_cast<int>(std::lround(k)));
    TEST_COMPARE(std::abs(k - std::lround(k)), <, 1e-12);
  }
  TEST_EQUALITY(std::count(m.flatOf.begin(), m.flatOf.end(), -1), 0);
  return m;
}

TEUCHOS_UNIT_TEST(ExtrudedContact, SlabRepeatsTheQuadrilateralMesh) {
  const Meshes m = loadBoth(out, success);
  TEST_EQUALITY(m.slab.dim, 3);
  TEST_EQUALITY(m.slab.numNodes(), (kLayers + 1) * m.flat.numNodes());
  // Every (2D node, plane) pair exactly once.
  std::set<std::pair<int, int>> seen;
  for (int n = 0; n < m.slab.numNodes(); ++n) seen.insert({m.flatOf[n], m.plane[n]});
  TEST_EQUALITY(static_cast<int>(seen.size()), m.slab.numNodes());
  for (const char* name : {"cylinder", "block"}) {
    const contact::GmshBody& b2 = m.flat.body(name);
    const contact::GmshBody& b3 = m.slab.body(name);
    TEST_EQUALITY(static_cast<int>(b2.type), static_cast<int>(contact::ElementType::Quad4));
    TEST_EQUALITY(static_cast<int>(b3.type), static_cast<int>(contact::ElementType::Hex8));
    TEST_EQUALITY(b3.numElements(), kLayers * b2.numElements());
  }
  for (const char* name : {"cylinder_contact", "block_contact", "load", "ends"})
    TEST_EQUALITY(static_cast<int>(m.slab.boundary(name).type),
                  static_cast<int>(contact::ElementType::Quad4));
  TEST_EQUALITY(m.slab.boundary("block_contact").numEdges(),
                kLayers * m.flat.boundary("block_contact").numEdges());
  TEST_EQUALITY(m.slab.boundary("ends").numEdges(),
                2 * (m.flat.body("cylinder").numElements() + m.flat.body("block").numElements()));
}

std::vector<int> nodesOf(const contact::GmshBoundary& b) {
  std::set<int> s(b.edges.begin(), b.edges.end());
  return std::vector<int>(s.begin(), s.end());
}

TEUCHOS_UNIT_TEST(ExtrudedContact, NodeToFaceRowsAreTheNodeToSegmentRows) {
  const Meshes m = loadBoth(out, success);
  contact::ContactSearchOptions opt;
  opt.searchRadius = 0.1;
  opt.endTolerance = 1e-4;  // as the elastic contact problem sets it
  const auto rows2 = contact::makeMeshContactMaster(m.flat, "block_contact", opt)
                         ->rows(m.flat.coords, nodesOf(m.flat.boundary("cylinder_contact")));
  const auto rows3 = contact::makeMeshContactMaster(m.slab, "block_contact", opt)
                         ->rows(m.slab.coords, nodesOf(m.slab.boundary("cylinder_contact")));
  std::map<int, const contact::ContactRow*> flatRow;
  for (const auto& r : rows2.rows) flatRow[r.slaveNode] = &r;
  TEST_EQUALITY(rows3.rows.size(), (kLayers + 1) * rows2.rows.size());
  double worstGap = 0.0, worstNormal = 0.0, worstCoef = 0.0, offPlane = 0.0;
  int kindMismatch = 0;
  for (const auto& r : rows3.rows) {
    const auto it = flatRow.find(m.flatOf[r.slaveNode]);
    TEST_ASSERT(it != flatRow.end());
    const contact::ContactRow& f = *it->second;
    worstGap = std::max(worstGap, std::abs(r.gap - f.gap));
    worstNormal =
        std::max(worstNormal, std::abs(r.normal[0] - f.normal[0]) +
                                  std::abs(r.normal[1] - f.normal[1]) + std::abs(r.normal[2]));
    // A 2D interior point is a face's interior, an edge between layers or, on an end plane, a
    // point of a free edge; the contact point's vertex is a 3D corner. Only free ends must agree.
    if ((f.kind == contact::ProjectionKind::End) != (r.kind == contact::ProjectionKind::End))
      ++kindMismatch;
    std::map<std::pair<int, int>, double> sum;
    for (std::size_t e = 3; e < r.entries.size(); ++e) {
      const auto& en = r.entries[e];
      if (m.plane[en.node] != m.plane[r.slaveNode])
        offPlane = std::max(offPlane, std::abs(en.coef));
      else
        sum[{m.flatOf[en.node], en.component}] += en.coef;
    }
    for (std::size_t e = 2; e < f.entries.size(); ++e) {
      const auto& en = f.entries[e];
      worstCoef = std::max(worstCoef, std::abs(sum[{en.node, en.component}] - en.coef));
      sum.erase({en.node, en.component});
    }
    for (const auto& [k, v] : sum) worstCoef = std::max(worstCoef, std::abs(v));
  }
  out << "worst |gap3 - gap2| " << worstGap << ", normal " << worstNormal << ", coefficient "
      << worstCoef << ", off-plane coefficient " << offPlane << ", kind mismatches " << kindMismatch
      << "\n";
  // Rounding of the 2D and 3D closest-point computations (lengths in metres, R = 1).
  TEST_COMPARE(worstGap, <, 1e-14);
  TEST_COMPARE(worstNormal, <, 1e-12);
  TEST_COMPARE(worstCoef, <, 1e-12);
  TEST_COMPARE(offPlane, <, 1e-14);
  TEST_EQUALITY(kindMismatch, 0);
}

}  // namespace
