// 3D cells of the VTU output in VTK's node order: every Tet4, Tet10, Hex8 and Hex27 cell that
// stressPiece writes for a Gmsh mesh is checked against VTK's documented node layout (VTK's
// vtkTetra, vtkQuadraticTetra, vtkHexahedron and vtkTriquadraticHexahedron class documentation):
// the corners give a positive volume the way VTK orients them, every midside node is at the
// midpoint of the edge VTK assigns to its position, every face node at the centre of VTK's face,
// and the body node at the centre. The meshes are boxes (straight edges, planar faces), so these
// positions are exact up to Gmsh's rounding.
#include <Teuchos_UnitTestHarness.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "contact_ContactOutput.hpp"
#include "contact_ElasticContactProblem.hpp"
#include "contact_GmshMesh.hpp"

namespace {

using Vec = std::array<double, 3>;

// VTK's documented layouts: the corners of each midside node's edge, of each face node's face.
const std::vector<std::array<int, 2>> kTetEdges{{0, 1}, {1, 2}, {2, 0}, {0, 3}, {1, 3}, {2, 3}};
const std::vector<std::array<int, 2>> kHexEdges{{0, 1}, {1, 2}, {2, 3}, {3, 0}, {4, 5}, {5, 6},
                                                {6, 7}, {7, 4}, {0, 4}, {1, 5}, {2, 6}, {3, 7}};
const std::vector<std::array<int, 4>> kHexFaces{{0, 3, 7, 4}, {1, 2, 6, 5}, {0, 1, 5, 4},
                                                {3, 2, 6, 7}, {0, 1, 2, 3}, {4, 5, 6, 7}};

double triple(const Vec& a, const Vec& b, const Vec& c) {
  return a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
         a[2] * (b[0] * c[1] - b[1] * c[0]);
}
Vec sub(const Vec& a, const Vec& b) {
  return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}
double dist(const Vec& a, const Vec& b) {
  const Vec d = sub(a, b);
  return std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
}
template <std::size_t N>
Vec mean(const std::vector<Vec>& p, const std::array<int, N>& idx) {
  Vec m{0, 0, 0};
  for (int i : idx)
    for (int c = 0; c < 3; ++c) m[c] += p[i][c] / N;
  return m;
}

// Loads the mesh, writes its cells through stressPiece and checks each against VTK's layout.
// Returns the number of cells checked.
int checkCells(const std::string& geo, int order, int expectedVtkType, Teuchos::FancyOStream& out,
               bool& success) {
  contact::MeshOptions opt;
  opt.order = order;
  const contact::GmshMesh mesh =
      contact::loadMesh(std::string(CONTACT_TEST_MESH_DIR) + "/" + geo, opt);
  const contact::GmshBody& body = mesh.bodies.front();
  const plasticity::ElementMesh em{contact::checkedBodyType(body.type), mesh.coords,
                                   body.connectivity};
  const std::vector<double> u(3 * em.numNodes(), 0.0);
  const plasticity::LinearElasticMaterial law(plasticity::ElasticLaw(1.0, 0.25));
  const plasticity::StressField stress = plasticity::recoverStresses(em, law, u);
  const contact::VtuPiece piece = contact::stressPiece({{&em, 0, &u, &stress, {}}});
  TEST_EQUALITY(piece.dim, 3);
  const int npe = contact::vtkCellSize(expectedVtkType);
  TEST_EQUALITY(static_cast<int>(piece.cellTypes.size()), em.numElements());
  const bool tet =
      expectedVtkType == contact::kVtkTetra || expectedVtkType == contact::kVtkQuadraticTetra;
  int checked = 0;
  for (int e = 0; e < em.numElements(); ++e) {
    TEST_EQUALITY(piece.cellTypes[e], expectedVtkType);
    std::vector<Vec> p(npe);
    for (int k = 0; k < npe; ++k)
      for (int c = 0; c < 3; ++c) p[k][c] = piece.points[3 * piece.cellPoints[e * npe + k] + c];
    // VTK's orientation: corner 3 (tetra) or 4 (hexahedron) above the face 0-1-2 (0-1-2-3)
    // traversed counter-clockwise, i.e. a positive triple product.
    const double vol = tet ? triple(sub(p[1], p[0]), sub(p[2], p[0]), sub(p[3], p[0]))
                           : triple(sub(p[1], p[0]), sub(p[3], p[0]), sub(p[4], p[0]));
    TEST_ASSERT(vol > 0.0);
    // Gmsh places midside nodes to about 1e-12; a wrong node would be a quarter edge off.
    const double h = dist(p[0], p[1]), tol = 1e-9 * h;
    const int corners = tet ? 4 : 8;
    if (npe > corners) {
      const auto& edges = tet ? kTetEdges : kHexEdges;
      for (std::size_t k = 0; k < edges.size(); ++k)
        TEST_COMPARE(dist(p[corners + k], mean(p, edges[k])), <, tol);
      if (!tet) {
        for (std::size_t f = 0; f < kHexFaces.size(); ++f)
          TEST_COMPARE(dist(p[20 + f], mean(p, kHexFaces[f])), <, tol);
        TEST_COMPARE(dist(p[26], mean(p, std::array<int, 8>{0, 1, 2, 3, 4, 5, 6, 7})), <, tol);
      }
    }
    ++checked;
  }
  out << geo << " order " << order << ": " << checked << " VTK cells of type " << expectedVtkType
      << " checked\n";
  return checked;
}

TEUCHOS_UNIT_TEST(VtkCells3D, TetrahedraInVtkOrder) {
  TEST_COMPARE(checkCells("box_tet.geo", 1, contact::kVtkTetra, out, success), >, 0);
  TEST_COMPARE(checkCells("box_tet.geo", 2, contact::kVtkQuadraticTetra, out, success), >, 0);
}

TEUCHOS_UNIT_TEST(VtkCells3D, HexahedraInVtkOrder) {
  TEST_COMPARE(checkCells("box_hex.geo", 1, contact::kVtkHexahedron, out, success), >, 0);
  TEST_COMPARE(checkCells("box_hex.geo", 2, contact::kVtkTriquadraticHexahedron, out, success), >,
               0);
}

// The permutations are permutations, and the Gmsh order itself would fail the layout check
// (Tet10 nodes 8 and 9, Hex27 edges and faces differ), so the test above can fail.
TEUCHOS_UNIT_TEST(VtkCells3D, OrdersArePermutations) {
  for (auto t : {plasticity::ElementType::Tet4, plasticity::ElementType::Tet10,
                 plasticity::ElementType::Hex8, plasticity::ElementType::Hex20,
                 plasticity::ElementType::Hex27}) {
    std::vector<int> o = plasticity::vtkNodeOrder(t);
    TEST_EQUALITY(static_cast<int>(o.size()), plasticity::nodesPerElement(t));
    std::sort(o.begin(), o.end());
    for (std::size_t k = 0; k < o.size(); ++k) TEST_EQUALITY(o[k], static_cast<int>(k));
  }
  TEST_INEQUALITY(plasticity::vtkNodeOrder(plasticity::ElementType::Tet10)[8], 8);
  TEST_INEQUALITY(plasticity::vtkNodeOrder(plasticity::ElementType::Hex27)[9], 9);
}

}  // namespace
