#pragma once
// Isoparametric plane-strain elements of Gmsh's families (3- and 6-node triangles, 4- and
// 9-node quadrilaterals) and Kokkos kernels assembling stiffness, loads and recovered stresses
// from them. Unknowns: 2 per node, interleaved (dof 2*node + component).
//
// Node ordering is Gmsh's, so that connectivity read from a .msh file needs no permutation:
// corner nodes counter-clockwise, then edge mid-nodes starting with edge 0-1 (edge k joins
// corners k and k+1 mod corners), then for Quad9 the centre.
//
//   Tri3 / Tri6, reference (xi, eta) in      Quad4 / Quad9, reference [-1, 1]^2:
//   the triangle (0,0), (1,0), (0,1):
//                                            3 ---- 6 ---- 2
//   2                                        |             |
//   | \                                      7      8      5
//   5   4                                    |             |
//   |     \                                  0 ---- 4 ---- 1
//   0 -- 3 -- 1
//
// Gauss rules (full integration: exact for the stiffness of an undistorted element, i.e. a
// straight-sided triangle or a parallelogram, where B^T D B det J is a polynomial):
//   Tri3  1 point (centroid)          B constant
//   Tri6  3 points (1/6, 1/6), ...    B linear, integrand quadratic: degree-2 rule
//   Quad4 2 x 2 Gauss-Legendre        integrand of degree 2 in each of xi, eta
//   Quad9 3 x 3 Gauss-Legendre        integrand of degree 4 in each of xi, eta
// On such elements the same rules also integrate the consistent body force exactly (on a curved
// Tri6 only its total is exact), and with them the elements have no spurious zero-energy modes.
#include <Kokkos_Core_fwd.hpp>  // KOKKOS_INLINE_FUNCTION and View declarations; kernels in .cpp

#include <cmath>
#include <string>
#include <vector>

#include "plasticity_ElasticLaw.hpp"
#include "plasticity_MaterialLaw.hpp"
#include "tfeti_CsrMatrix.hpp"

namespace plasticity {

enum class ElementType { Tri3, Quad4, Tri6, Quad9 };

// Bounds for fixed-size per-element arrays inside kernels.
constexpr int kMaxElementNodes = 9;
constexpr int kMaxGaussPoints = 9;

KOKKOS_INLINE_FUNCTION int nodesPerElement(ElementType t) {
  return t == ElementType::Tri3 ? 3 : t == ElementType::Quad4 ? 4 : t == ElementType::Tri6 ? 6 : 9;
}
KOKKOS_INLINE_FUNCTION int cornersPerElement(ElementType t) {
  return t == ElementType::Tri3 || t == ElementType::Tri6 ? 3 : 4;
}
KOKKOS_INLINE_FUNCTION bool isQuadratic(ElementType t) {
  return t == ElementType::Tri6 || t == ElementType::Quad9;
}
// Nodes on one element edge: 2 for linear elements, 3 (end, end, middle: Gmsh's line3) else.
KOKKOS_INLINE_FUNCTION int nodesPerEdge(ElementType t) {
  return isQuadratic(t) ? 3 : 2;
}
KOKKOS_INLINE_FUNCTION int numGaussPoints(ElementType t) {
  return t == ElementType::Tri3 ? 1 : t == ElementType::Quad4 ? 4 : t == ElementType::Tri6 ? 3 : 9;
}
std::string elementTypeName(ElementType t);

// Shape functions N[a] and their reference derivatives dN[a] = (dN/dxi, dN/deta) at (xi, eta).
KOKKOS_INLINE_FUNCTION void shapeFunctions(ElementType t, double xi, double eta, double N[],
                                           double dN[][2]) {
  switch (t) {
    case ElementType::Tri3:
      N[0] = 1 - xi - eta, N[1] = xi, N[2] = eta;
      dN[0][0] = -1, dN[0][1] = -1;
      dN[1][0] = 1, dN[1][1] = 0;
      dN[2][0] = 0, dN[2][1] = 1;
      break;
    case ElementType::Tri6: {
      // Written in area coordinates; L0 depends on both xi and eta.
      const double L0 = 1 - xi - eta, L1 = xi, L2 = eta;
      N[0] = L0 * (2 * L0 - 1), N[1] = L1 * (2 * L1 - 1), N[2] = L2 * (2 * L2 - 1);
      N[3] = 4 * L0 * L1, N[4] = 4 * L1 * L2, N[5] = 4 * L2 * L0;
      dN[0][0] = 1 - 4 * L0, dN[0][1] = 1 - 4 * L0;
      dN[1][0] = 4 * L1 - 1, dN[1][1] = 0;
      dN[2][0] = 0, dN[2][1] = 4 * L2 - 1;
      dN[3][0] = 4 * (L0 - L1), dN[3][1] = -4 * L1;
      dN[4][0] = 4 * L2, dN[4][1] = 4 * L1;
      dN[5][0] = -4 * L2, dN[5][1] = 4 * (L0 - L2);
      break;
    }
    case ElementType::Quad4: {
      const double sx[4] = {-1, 1, 1, -1}, sy[4] = {-1, -1, 1, 1};
      for (int a = 0; a < 4; ++a) {
        N[a] = 0.25 * (1 + sx[a] * xi) * (1 + sy[a] * eta);
        dN[a][0] = 0.25 * sx[a] * (1 + sy[a] * eta);
        dN[a][1] = 0.25 * sy[a] * (1 + sx[a] * xi);
      }
      break;
    }
    case ElementType::Quad9: {
      // Tensor product of 1D quadratic Lagrange polynomials at -1, 0, 1 (indices 0, 1, 2).
      const double lx[3] = {0.5 * xi * (xi - 1), 1 - xi * xi, 0.5 * xi * (xi + 1)};
      const double ly[3] = {0.5 * eta * (eta - 1), 1 - eta * eta, 0.5 * eta * (eta + 1)};
      const double dx[3] = {xi - 0.5, -2 * xi, xi + 0.5};
      const double dy[3] = {eta - 0.5, -2 * eta, eta + 0.5};
      const int ix[9] = {0, 2, 2, 0, 1, 2, 1, 0, 1}, iy[9] = {0, 0, 2, 2, 0, 1, 2, 1, 1};
      for (int a = 0; a < 9; ++a) {
        N[a] = lx[ix[a]] * ly[iy[a]];
        dN[a][0] = dx[ix[a]] * ly[iy[a]];
        dN[a][1] = lx[ix[a]] * dy[iy[a]];
      }
      break;
    }
  }
}

// Reference coordinates of node a.
KOKKOS_INLINE_FUNCTION void referenceNode(ElementType t, int a, double& xi, double& eta) {
  if (cornersPerElement(t) == 3) {
    const double r[6][2] = {{0, 0}, {1, 0}, {0, 1}, {0.5, 0}, {0.5, 0.5}, {0, 0.5}};
    xi = r[a][0], eta = r[a][1];
  } else {
    const double r[9][2] = {{-1, -1}, {1, -1}, {1, 1},  {-1, 1}, {0, -1},
                            {1, 0},   {0, 1},  {-1, 0}, {0, 0}};
    xi = r[a][0], eta = r[a][1];
  }
}

// Gauss point q of the element's rule: reference position and weight (the weights sum to the
// reference area, 1/2 or 4). Quadrilateral points run with xi fastest, from -1 towards +1.
KOKKOS_INLINE_FUNCTION void gaussPoint(ElementType t, int q, double& xi, double& eta, double& w) {
  xi = eta = w = 0;  // every enumerator is handled; this only quiets -Wmaybe-uninitialized
  switch (t) {
    case ElementType::Tri3:
      xi = eta = 1.0 / 3.0, w = 0.5;
      break;
    case ElementType::Tri6: {
      const double a = 1.0 / 6.0, b = 2.0 / 3.0;
      xi = q == 1 ? b : a, eta = q == 2 ? b : a, w = 1.0 / 6.0;
      break;
    }
    case ElementType::Quad4: {
      const double g = 0.57735026918962576451;  // 1/sqrt(3)
      xi = q % 2 ? g : -g, eta = q / 2 ? g : -g, w = 1.0;
      break;
    }
    case ElementType::Quad9: {
      const double p[3] = {-0.77459666924148337704, 0.0, 0.77459666924148337704};  // sqrt(3/5)
      const double wt[3] = {5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0};
      xi = p[q % 3], eta = p[q / 3], w = wt[q % 3] * wt[q / 3];
      break;
    }
  }
}

// Shape functions and their x, y derivatives at (xi, eta) for the element nodes x (x, y per
// node); returns the Jacobian determinant.
KOKKOS_INLINE_FUNCTION double physicalGradients(ElementType t, const double* x, double xi,
                                                double eta, double N[], double dNdx[][2]) {
  const int npe = nodesPerElement(t);
  double dN[kMaxElementNodes][2];
  shapeFunctions(t, xi, eta, N, dN);
  double J[2][2] = {{0, 0}, {0, 0}};  // J[i][j] = d x_i / d xi_j
  for (int a = 0; a < npe; ++a)
    for (int i = 0; i < 2; ++i)
      for (int j = 0; j < 2; ++j) J[i][j] += x[2 * a + i] * dN[a][j];
  const double det = J[0][0] * J[1][1] - J[0][1] * J[1][0];
  const double inv[2][2] = {{J[1][1] / det, -J[0][1] / det}, {-J[1][0] / det, J[0][0] / det}};
  for (int a = 0; a < npe; ++a)
    for (int j = 0; j < 2; ++j) dNdx[a][j] = dN[a][0] * inv[0][j] + dN[a][1] * inv[1][j];
  return det;
}

// A mesh of one element type. Elements must be counter-clockwise (positive Jacobian).
struct ElementMesh {
  ElementType type = ElementType::Quad4;
  std::vector<double> coords;     // x, y per node
  std::vector<int> connectivity;  // nodesPerElement(type) per element, Gmsh order
  int numNodes() const { return static_cast<int>(coords.size() / 2); }
  int numElements() const { return static_cast<int>(connectivity.size()) / nodesPerElement(type); }
};

// Stiffness matrix (tangent of the law at zero strain) of the whole mesh, 2 dofs per node;
// the pattern holds every node pair sharing an element. Throws std::invalid_argument naming
// the element when connectivity is out of range or the Jacobian determinant is not positive
// at some Gauss point or node.
tfeti::CsrMatrix assembleStiffness(const ElementMesh& mesh, const MaterialLaw& law);
tfeti::CsrMatrix assembleStiffness(const ElementMesh& mesh, const ElasticLaw& law);

// Consistent nodal forces of a uniform body force b (force per unit volume; per unit area of
// the unit-thickness plane-strain slice).
std::vector<double> assembleBodyForce(const ElementMesh& mesh, const double b[2]);

// Consistent nodal forces of a uniform traction t on the given edges: t is force per unit edge
// length (i.e. stress times the unit out-of-plane thickness), and the nodal forces are forces
// per unit thickness. `edges` lists nodesPerEdge(mesh.type) nodes per edge, Gmsh line order
// (the two end nodes, then for quadratic elements the middle node); each must be an edge of
// some element, which catches edges of the wrong order or with a misplaced middle node.
// Throws std::invalid_argument naming the edge otherwise.
std::vector<double> assembleEdgeTraction(const ElementMesh& mesh, const std::vector<int>& edges,
                                         const double t[2]);

// Stress components as stored in StressField, per Gauss point and per node.
enum StressComponent { kSxx = 0, kSyy, kSxy, kSzz, kVonMises, kNumStressComponents };

struct StressField {
  int gaussPointsPerElement = 0;
  // [(e * gaussPointsPerElement + q) * kNumStressComponents + c]: the law's stress at the
  // Gauss point (the only place a history-dependent law has it), and its von Mises value.
  std::vector<double> gauss;
  // [(e * gaussPointsPerElement + q) * 2 + i]: physical position of the Gauss point.
  std::vector<double> gaussCoords;
  // [n * kNumStressComponents + c]: per element, the Gauss-point stresses are extrapolated to
  // the element's nodes (by the polynomial through the Gauss points: constant for Tri3, linear
  // for Tri6, bilinear for Quad4, biquadratic for Quad9) and the node takes the mean over the
  // elements sharing it. Von Mises is the invariant of the averaged tensor.
  std::vector<double> nodal;

  double atGaussPoint(int e, int q, int c) const {
    return gauss[(static_cast<std::size_t>(e) * gaussPointsPerElement + q) * kNumStressComponents +
                 c];
  }
  double atNode(int n, int c) const {
    return nodal[static_cast<std::size_t>(n) * kNumStressComponents + c];
  }
};

// Von Mises equivalent stress including sigma_zz: sqrt(3 J2). Host-only (std::sqrt), as are
// the kernels on the Serial backend.
KOKKOS_INLINE_FUNCTION double vonMises(double sxx, double syy, double sxy, double szz) {
  const double a = sxx - syy, b = syy - szz, c = szz - sxx;
  return std::sqrt(0.5 * (a * a + b * b + c * c) + 3 * sxy * sxy);
}

// Stresses of the displacement u (2 dofs per node) through the law.
StressField recoverStresses(const ElementMesh& mesh, const MaterialLaw& law,
                            const std::vector<double>& u);

// Building blocks shared with the other kernel files of this package (plasticity_TotalLagrangian),
// so that they validate, gather and scatter exactly as these kernels do. Not a user API.
namespace detail {
using HostView2 = Kokkos::View<double**, Kokkos::HostSpace>;
using HostView3 = Kokkos::View<double***, Kokkos::HostSpace>;
// "<type> element <e>", the prefix of every per-element error message.
std::string elementLabel(const ElementMesh& mesh, int e);
// Validated element coordinates (ne, 2 npe); throws as assembleStiffness does.
HostView2 checkedElementCoords(const ElementMesh& mesh);
// Element displacements (ne, 2 npe); throws when u does not have 2 entries per node.
HostView2 elementDisplacements(const ElementMesh& mesh, const std::vector<double>& u);
// CSR matrix (node pairs sharing an element, 2 dofs each) summing the element blocks Ke.
tfeti::CsrMatrix scatterStiffness(const ElementMesh& mesh, const HostView3& Ke);
// The StressField of Gauss-point stresses sg (ne, ngp, 4: xx, yy, xy, zz) at positions xg
// (ne, ngp, 2): von Mises added, nodal values extrapolated and averaged.
StressField stressField(const ElementMesh& mesh, const HostView3& sg, const HostView3& xg);
}  // namespace detail

}  // namespace plasticity
