// Loading 3D meshes through Gmsh: .geo files with volumes meshed at run time (tetrahedra,
// transfinite hexahedra, orders 1 and 2), a stored Hex20 .msh, checked against what is exactly
// known about them: the volume of a box, the area of its faces, nodes on the sphere they were
// placed on, midside nodes at the midpoints of straight edges, and every element facet oriented
// outward. The boundary faces' relation to their body element. And the error paths: a mesh of
// the wrong dimension, inverted and degenerate elements (naming the element's Gmsh tag).
#include <Teuchos_UnitTestHarness.hpp>

#include <array>
#include <cmath>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "contact_GmshMesh.hpp"

namespace {

using contact::ElementType;
using contact::GmshMesh;
using contact::loadMesh;
using Vec3 = std::array<double, 3>;

const std::string kMeshDir = CONTACT_TEST_MESH_DIR;

std::string meshFile(const std::string& name) {
  return kMeshDir + "/" + name;
}

contact::MeshOptions opts(int order, double sizeFactor = 1.0) {
  contact::MeshOptions o;
  o.order = order;
  o.sizeFactor = sizeFactor;
  return o;
}

Vec3 at(const GmshMesh& m, int n) {
  return {m.coords[3 * n], m.coords[3 * n + 1], m.coords[3 * n + 2]};
}
Vec3 sub(const Vec3& a, const Vec3& b) {
  return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}
Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
double dot(const Vec3& a, const Vec3& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
double norm(const Vec3& a) {
  return std::sqrt(dot(a, a));
}

Vec3 centroid(const GmshMesh& m, const int* nodes, int count) {
  Vec3 c{0, 0, 0};
  for (int k = 0; k < count; ++k)
    for (int i = 0; i < 3; ++i) c[i] += at(m, nodes[k])[i] / count;
  return c;
}

// Area vector of a planar facet from its corners (triangle or quadrangle): |v| is the area.
Vec3 areaVector(const GmshMesh& m, const std::vector<int>& corners) {
  Vec3 v{0, 0, 0};
  for (std::size_t k = 1; k + 1 < corners.size(); ++k) {
    const Vec3 c = cross(sub(at(m, corners[k]), at(m, corners[0])),
                         sub(at(m, corners[k + 1]), at(m, corners[0])));
    for (int i = 0; i < 3; ++i) v[i] += 0.5 * c[i];
  }
  return v;
}

// Signed volume of a straight-sided element: a tetrahedron, or a parallelepiped hexahedron
// (every hexahedron of the box meshes), from corner 0 and its neighbours.
double straightVolume(const GmshMesh& m, ElementType type, const int* el) {
  const Vec3 x0 = at(m, el[0]);
  if (contact::numCorners(type) == 4)
    return dot(cross(sub(at(m, el[1]), x0), sub(at(m, el[2]), x0)), sub(at(m, el[3]), x0)) / 6.0;
  return dot(cross(sub(at(m, el[1]), x0), sub(at(m, el[3]), x0)), sub(at(m, el[4]), x0));
}

// Every facet of every element: outward (its corners' normal points away from the element's
// centroid), the node count of its type, and (straight meshes) midside nodes at the midpoints of
// the facet's edges and a face centre at the centroid. Returns the number of facets checked.
int checkFacets(Teuchos::FancyOStream& out, bool& success, const GmshMesh& m,
                const contact::GmshBody& b, bool straight) {
  const int npe = b.nodesPerElement(), nc = contact::numCorners(b.type);
  const ElementType ft = contact::facetType(b.type);
  const int fc = contact::numCorners(ft);
  int checked = 0;
  for (int e = 0; e < b.numElements(); ++e) {
    const int* el = &b.connectivity[static_cast<std::size_t>(e) * npe];
    const Vec3 ce = centroid(m, el, nc);
    for (int f = 0; f < contact::numFacets(b.type); ++f) {
      const std::vector<int>& local = contact::elementFacetNodes(b.type, f);
      TEST_EQUALITY(static_cast<int>(local.size()), contact::numNodes(ft));
      std::vector<int> nodes;
      for (int k : local) nodes.push_back(el[k]);
      const std::vector<int> corners(nodes.begin(), nodes.begin() + fc);
      const Vec3 cf = centroid(m, corners.data(), fc);
      TEST_COMPARE(dot(areaVector(m, corners), sub(cf, ce)), >, 0.0);
      if (straight) {
        for (int j = 0; j<fc&& static_cast<int>(nodes.size())> fc; ++j) {
          const Vec3 a = at(m, corners[j]), c = at(m, corners[(j + 1) % fc]);
          const Vec3 mid{0.5 * (a[0] + c[0]), 0.5 * (a[1] + c[1]), 0.5 * (a[2] + c[2])};
          TEST_COMPARE(norm(sub(at(m, nodes[fc + j]), mid)), <, 1e-9);
        }
        if (ft == ElementType::Quad9) TEST_COMPARE(norm(sub(at(m, nodes[8]), cf)), <, 1e-9);
      }
      ++checked;
    }
  }
  return checked;
}

// The boundary's faces are related to a facet of a body element with the same nodes, and the
// facet's outward unit normal is `normal` (planar boundaries). Returns the boundary's area.
double checkPlanarBoundary(Teuchos::FancyOStream& out, bool& success, const GmshMesh& m,
                           const std::string& name, const Vec3& normal) {
  const contact::GmshBoundary& g = m.boundary(name);
  TEST_EQUALITY(g.nodesPerEdge, contact::numNodes(g.type));
  double area = 0.0;
  for (int i = 0; i < g.numEdges(); ++i) {
    TEST_COMPARE(g.edgeElement[i], >=, 0);
    if (g.edgeElement[i] < 0) continue;
    const contact::GmshBody& b = m.bodies[g.edgeBody[i]];
    TEST_EQUALITY(static_cast<int>(contact::facetType(b.type)), static_cast<int>(g.type));
    const int* el =
        &b.connectivity[static_cast<std::size_t>(g.edgeElement[i]) * b.nodesPerElement()];
    std::set<int> facet,
        face(g.edges.begin() + i * g.nodesPerEdge, g.edges.begin() + (i + 1) * g.nodesPerEdge);
    std::vector<int> corners;
    const std::vector<int>& local = contact::elementFacetNodes(b.type, g.edgeLocalEdge[i]);
    for (int k : local) facet.insert(el[k]);
    for (int k = 0; k < contact::numCorners(g.type); ++k) corners.push_back(el[local[k]]);
    TEST_ASSERT(facet == face);
    const Vec3 av = areaVector(m, corners);
    TEST_COMPARE(norm(sub(av, {normal[0] * norm(av), normal[1] * norm(av), normal[2] * norm(av)})),
                 <, 1e-12);
    area += norm(av);
  }
  return area;
}

TEUCHOS_UNIT_TEST(GmshMesh3D, TetrahedraOfTheUnitCube) {
  for (int order : {1, 2}) {
    const GmshMesh m = loadMesh(meshFile("box_tet.geo"), opts(order));
    TEST_EQUALITY(m.dim, 3);
    TEST_EQUALITY(m.coords.size(), 3 * m.gmshNodes.size());
    TEST_EQUALITY(m.bodies.size(), 1u);
    const contact::GmshBody& b = m.body("cube");
    TEST_EQUALITY(plasticity::gmshType(b.type), order == 1 ? 4 : 11);
    double volume = 0.0, smallest = 1.0;
    for (int e = 0; e < b.numElements(); ++e) {
      const double v = straightVolume(m, b.type, &b.connectivity[e * b.nodesPerElement()]);
      volume += v;
      smallest = std::min(smallest, v);
    }
    TEST_COMPARE(std::abs(volume - 1.0), <, 1e-10);
    TEST_COMPARE(smallest, >, 0.0);
    TEST_COMPARE(b.numElements(), >=, 24);
    TEST_EQUALITY(checkFacets(out, success, m, b, true), 4 * b.numElements());
    const double top = checkPlanarBoundary(out, success, m, "top", {0, 0, 1});
    const double bottom = checkPlanarBoundary(out, success, m, "bottom", {0, 0, -1});
    const double xmin = checkPlanarBoundary(out, success, m, "xmin", {-1, 0, 0});
    const double ymax = checkPlanarBoundary(out, success, m, "ymax", {0, 1, 0});
    for (double a : {top, bottom, xmin, ymax}) TEST_COMPARE(std::abs(a - 1.0), <, 1e-10);
    TEST_EQUALITY(plasticity::gmshType(m.boundary("top").type), order == 1 ? 2 : 9);
  }
}

TEUCHOS_UNIT_TEST(GmshMesh3D, HexahedraOfABox) {
  // Order 1 and 2 from the .geo (Hex8, Hex27), and the serendipity Hex20 from a stored .msh.
  struct Case {
    std::string file;
    int order, type, faceType;
  };
  for (const Case& c : {Case{"box_hex.geo", 1, 5, 3}, Case{"box_hex.geo", 2, 12, 10},
                        Case{"box_hex20.msh", 1, 17, 16}}) {
    const GmshMesh m = loadMesh(meshFile(c.file), opts(c.order));
    TEST_EQUALITY(m.dim, 3);
    const contact::GmshBody& b = m.body("box");
    TEST_EQUALITY(plasticity::gmshType(b.type), c.type);
    TEST_EQUALITY(b.numElements(), 8);
    double volume = 0.0;
    for (int e = 0; e < b.numElements(); ++e) {
      const double v = straightVolume(m, b.type, &b.connectivity[e * b.nodesPerElement()]);
      TEST_COMPARE(std::abs(v - 0.25), <, 1e-10);  // (2 x 1 x 1) / 8, positively oriented
      volume += v;
    }
    TEST_COMPARE(std::abs(volume - 2.0), <, 1e-10);
    TEST_EQUALITY(checkFacets(out, success, m, b, true), 6 * 8);
    TEST_EQUALITY(plasticity::gmshType(m.boundary("top").type), c.faceType);
    TEST_COMPARE(std::abs(checkPlanarBoundary(out, success, m, "top", {0, 0, 1}) - 2.0), <, 1e-10);
    TEST_COMPARE(std::abs(checkPlanarBoundary(out, success, m, "bottom", {0, 0, -1}) - 2.0), <,
                 1e-12);
    TEST_EQUALITY(m.boundary("sides").numEdges(), 4 * 4);  // 2 x 2 faces on each side
  }
}

TEUCHOS_UNIT_TEST(GmshMesh3D, QuarterSphereOnABlock) {
  const double R = 1.0;
  const Vec3 centre{0, 0, R};
  for (int order : {1, 2}) {
    const GmshMesh m = loadMesh(meshFile("sphere_on_block.geo"), opts(order));
    TEST_EQUALITY(m.dim, 3);
    TEST_EQUALITY(m.bodies.size(), 2u);
    const int sphere = m.bodyIndex("sphere"), block = m.bodyIndex("block");
    // Volumes: the block exactly; the inscribed sphere mesh a little less than pi R^3 / 6
    // (for order 2, the straight-sided volume of the curved elements' corners).
    double vs = 0.0, vb = 0.0;
    for (int which : {sphere, block}) {
      const contact::GmshBody& b = m.bodies[which];
      for (int e = 0; e < b.numElements(); ++e)
        (which == sphere ? vs : vb) +=
            straightVolume(m, b.type, &b.connectivity[e * b.nodesPerElement()]);
      checkFacets(out, success, m, b, false);
    }
    const double exact = M_PI * R * R * R / 6.0;
    TEST_COMPARE(std::abs(vb - 4.0), <, 1e-10);
    TEST_COMPARE(vs, <, exact);
    TEST_COMPARE(vs, >, 0.9 * exact);
    // The sphere's contact faces: every node on the sphere (midside nodes placed on the geometry
    // too), related to the sphere's elements, outward normals pointing away from the centre.
    const contact::GmshBoundary& g = m.boundary("sphere_contact");
    double worst = 0.0;
    for (int n : g.edges) worst = std::max(worst, std::abs(norm(sub(at(m, n), centre)) - R));
    TEST_COMPARE(worst, <, 1e-6);
    for (int i = 0; i < g.numEdges(); ++i) {
      TEST_EQUALITY(g.edgeBody[i], sphere);
      const contact::GmshBody& b = m.bodies[sphere];
      const int* el =
          &b.connectivity[static_cast<std::size_t>(g.edgeElement[i]) * b.nodesPerElement()];
      std::vector<int> corners;
      for (int k = 0; k < 3; ++k)
        corners.push_back(el[contact::elementFacetNodes(b.type, g.edgeLocalEdge[i])[k]]);
      TEST_COMPARE(dot(areaVector(m, corners), sub(centroid(m, corners.data(), 3), centre)), >,
                   0.0);
    }
    const double top = checkPlanarBoundary(out, success, m, "block_contact", {0, 0, 1});
    TEST_COMPARE(std::abs(top - 4.0), <, 1e-10);
    for (int i = 0; i < m.boundary("block_contact").numEdges(); ++i)
      TEST_EQUALITY(m.boundary("block_contact").edgeBody[i], block);
  }
  // The size factor refines.
  const GmshMesh coarse = loadMesh(meshFile("sphere_on_block.geo"), opts(1));
  const GmshMesh fine = loadMesh(meshFile("sphere_on_block.geo"), opts(1, 0.5));
  TEST_COMPARE(fine.body("sphere").numElements(), >, 4 * coarse.body("sphere").numElements());
}

TEUCHOS_UNIT_TEST(GmshMesh3D, FacetTablesOfEveryType) {
  // Facet counts and facet types; facet node lists are distinct local nodes.
  struct Case {
    ElementType type, facet;
    int facets;
  };
  for (const Case& c : {Case{ElementType::Tet4, ElementType::Tri3, 4},
                        Case{ElementType::Tet10, ElementType::Tri6, 4},
                        Case{ElementType::Hex8, ElementType::Quad4, 6},
                        Case{ElementType::Hex20, ElementType::Quad8, 6},
                        Case{ElementType::Hex27, ElementType::Quad9, 6},
                        Case{ElementType::Tri6, ElementType::Line3, 3},
                        Case{ElementType::Quad4, ElementType::Line2, 4}}) {
    TEST_EQUALITY(contact::numFacets(c.type), c.facets);
    TEST_EQUALITY(static_cast<int>(contact::facetType(c.type)), static_cast<int>(c.facet));
    std::multiset<int> used;
    for (int f = 0; f < c.facets; ++f) {
      const std::vector<int>& nodes = contact::elementFacetNodes(c.type, f);
      TEST_EQUALITY(std::set<int>(nodes.begin(), nodes.end()).size(), nodes.size());
      for (int k : nodes) used.insert(k);
    }
    // Each corner of a tetrahedron is on 3 faces, of a hexahedron on 3 faces.
    if (contact::elementDimension(c.type) == 3)
      for (int k = 0; k < contact::numCorners(c.type); ++k) TEST_EQUALITY(used.count(k), 3u);
  }
  TEST_THROW(contact::elementFacetNodes(ElementType::Hex8, 6), std::out_of_range);
  TEST_THROW(contact::facetType(ElementType::Quad8), std::invalid_argument);
}

// The error's message, or "" when `load` does not throw E.
template <class E, class F>
std::string messageOf(F&& load) {
  try {
    load();
  } catch (const E& e) {
    return e.what();
  }
  return "";
}

bool contains(const std::string& s, const std::string& part) {
  return s.find(part) != std::string::npos;
}

TEUCHOS_UNIT_TEST(GmshMesh3D, WrongDimensionIsAnErrorNamingTheFile) {
  contact::MeshOptions want3 = opts(1), want2 = opts(1);
  want3.dimension = 3;
  want2.dimension = 2;
  const std::string a =
      messageOf<std::invalid_argument>([&] { loadMesh(meshFile("rectangle.geo"), want3); });
  TEST_ASSERT(contains(a, "rectangle.geo") && contains(a, "is 2D") && contains(a, "3D problem"));
  const std::string b =
      messageOf<std::invalid_argument>([&] { loadMesh(meshFile("box_tet.geo"), want2); });
  TEST_ASSERT(contains(b, "box_tet.geo") && contains(b, "is 3D") && contains(b, "2D problem"));
  const std::string c =
      messageOf<std::invalid_argument>([&] { loadMesh(meshFile("box_hex20.msh"), want2); });
  TEST_ASSERT(contains(c, "box_hex20.msh") && contains(c, "is 3D"));
  // Accepted with the matching or an open dimension.
  TEST_EQUALITY(loadMesh(meshFile("box_tet.geo"), want3).dim, 3);
  TEST_EQUALITY(loadMesh(meshFile("rectangle.geo"), want2).dim, 2);
  TEST_EQUALITY(loadMesh(meshFile("rectangle.geo")).dim, 2);
  contact::MeshOptions quads = opts(1);
  quads.quads = true;
  const std::string d =
      messageOf<std::invalid_argument>([&] { loadMesh(meshFile("box_tet.geo"), quads); });
  TEST_ASSERT(contains(d, "box_tet.geo") && contains(d, "2D only"));
  contact::MeshOptions badDim = opts(1);
  badDim.dimension = 1;
  TEST_THROW(loadMesh(meshFile("box_tet.geo"), badDim), std::invalid_argument);
}

TEUCHOS_UNIT_TEST(GmshMesh3D, InvertedAndDegenerateElementsAreRejected) {
  const std::string inverted =
      messageOf<std::runtime_error>([&] { loadMesh(meshFile("tet_inverted.msh")); });
  out << inverted << "\n";
  TEST_ASSERT(contains(inverted, "tet_inverted.msh") && contains(inverted, "element 7 ") &&
              contains(inverted, "inverted") && contains(inverted, "\"solid\""));
  const std::string flat =
      messageOf<std::runtime_error>([&] { loadMesh(meshFile("tet_degenerate.msh")); });
  out << flat << "\n";
  TEST_ASSERT(contains(flat, "tet_degenerate.msh") && contains(flat, "element 7 ") &&
              contains(flat, "degenerate"));
  const std::string flat2d =
      messageOf<std::runtime_error>([&] { loadMesh(meshFile("tri_degenerate.msh")); });
  out << flat2d << "\n";
  TEST_ASSERT(contains(flat2d, "tri_degenerate.msh") && contains(flat2d, "element 5 ") &&
              contains(flat2d, "degenerate"));
}

}  // namespace
