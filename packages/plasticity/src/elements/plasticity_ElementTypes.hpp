#pragma once
// The element catalogue: every element type the code knows -- isoparametric bodies of Gmsh's
// families in 2D and 3D, their faces, and the serendipity types a mesh file may hold -- and
// everything about each one: node count, dimension, order, corners, facets (type, count and
// local node lists), Gmsh type code, VTK cell type and node order, shape functions, Gauss rules
// and reference node positions. The mesh reader (contact_GmshMesh), the assembly
// (plasticity_Elements), the contact surfaces and the output (contact_ContactOutput,
// contact_VtuWriter) only ask it.
//
// A new element type needs, in this file and plasticity_ElementTypes.cpp only:
//  - a value of ElementType and its row of elementInfo() (dimension, order, nodes, corners,
//    Gauss points, facet and linear types, flags, Gmsh and VTK codes), and larger bounds below
//    (kMaxElementNodes, kMaxGaussPoints) if it exceeds them;
//  - its row of kCatalogue in the .cpp (short and Gmsh names; the row's place is the order of
//    type lists in messages) and, when VTK numbers its nodes otherwise than Gmsh, its VTK node
//    order there (vtkPermutations);
//  - when it opens a new family: its node table below (detail::tensorIndex, detail::simplexEdge),
//    shape functions and Gauss rule (shapeFunctions, gaussPoint), and its facet corners in the
//    .cpp (facetCorners).
// Everything else derives from these: the mesh reader's accepted types and their facets, the
// 2D reorientation, the partition's facets, the assembly, the VTK output. What stays per type
// elsewhere is the numerics of two contact methods, each throwing for a face type it does not
// know: the nodal area rule of a contact surface (contact_SurfaceWeights) and the face shape
// functions of the node-to-face search (contact_NodeToFace, which also serves Quad8).
//
// Node ordering is Gmsh's (checked against gmsh::model::mesh::getElementProperties), so that
// connectivity read from a .msh file needs no permutation.
//
// Simplices (Lagrange on barycentric coordinates L_0 = 1 - sum xi, L_k = xi_{k-1}): corners at
// the origin and the unit points, then for quadratic elements one node per edge at its middle,
// edges in Gmsh's order:
//   Tri3 / Tri6    corners 0 (0,0), 1 (1,0), 2 (0,1); edges 3: 0-1, 4: 1-2, 5: 2-0
//   Tet4 / Tet10   corners 0 (0,0,0), 1 (1,0,0), 2 (0,1,0), 3 (0,0,1);
//                  edges 4: 0-1, 5: 1-2, 6: 2-0, 7: 3-0, 8: 3-2, 9: 3-1
// Tensor products of 1D Lagrange polynomials on [-1, 1] (nodes at -1, 1, and 0 when quadratic):
//   Line2 / Line3  -1, 1, then the middle 0
//   Quad4 / Quad9  corners counter-clockwise from (-1,-1); mid-edges 4: 0-1, 5: 1-2, 6: 2-3,
//                  7: 3-0; centre 8
//   Hex8 / Hex27   corners 0-3 on zeta = -1 counter-clockwise from (-1,-1), 4-7 above them on
//                  zeta = 1; mid-edges 8: 0-1, 9: 0-3, 10: 0-4, 11: 1-2, 12: 1-5, 13: 2-3,
//                  14: 2-6, 15: 3-7, 16: 4-5, 17: 4-7, 18: 5-6, 19: 6-7; face centres 20: zeta
//                  = -1, 21: eta = -1, 22: xi = -1, 23: xi = 1, 24: eta = 1, 25: zeta = 1;
//                  centre 26
// Serendipity (incomplete) types, which Gmsh writes for second order with
// Mesh.SecondOrderIncomplete: a mesh file may hold them, the mesh reader takes Hex20 bodies and
// Quad8 faces, and the node-to-face search has Quad8's shape functions; the assembly has none
// (ElementInfo::complete is false: no shape functions or Gauss rule below).
//   Quad8 / Hex20  the first 8 / 20 nodes of Quad9 / Hex27
//
// Gauss rules (full integration: exact for the stiffness of an undistorted element -- straight
// sides, parallelogram/parallelepiped -- where B^T D B det J is a polynomial; on such elements
// they also integrate the consistent body force exactly, and the elements have no spurious
// zero-energy modes):
//   Tri3   1 point (centroid)             B constant
//   Tri6   3 points (1/6, 1/6), ...       B linear, integrand quadratic: degree-2 rule
//   Tet4   1 point (centroid)             B constant
//   Tet10  4 points (a,a,a), (b,a,a), ... a = (5 - sqrt 5)/20, b = (5 + 3 sqrt 5)/20: degree 2
//   Line2, Quad4, Hex8    2 per direction Gauss-Legendre   integrand degree 2 per direction
//   Line3, Quad9, Hex27   3 per direction Gauss-Legendre   integrand degree 4 per direction
// The faces' own rules integrate surface loads (exactly on flat faces).
//
// Quadratic hexahedra: Hex27 rather than the serendipity Hex20. Under a uniform pressure the
// consistent nodal forces of Hex20's 8-node faces are negative at the corners (-1/12 of the
// face load each), which a node-to-face contact discretization turns into spurious tensile
// multipliers at the slave corners; Hex27's Quad9 faces carry positive loads at every node
// (1/36, 4/36, 16/36), and Hex27 is what Gmsh produces for second order by default. It also
// extends the 2D Quad9 with the same code (the tensor product).
#include <Kokkos_Core_fwd.hpp>  // KOKKOS_INLINE_FUNCTION

#include <cmath>
#include <string>
#include <vector>

namespace plasticity {

// The enum lives in a namespace of its own so that argument-dependent lookup on an ElementType
// finds no plasticity function: other packages name their own queries on the catalogue
// (contact::elementTypeName, Gmsh's long name) without clashing with plasticity's.
namespace element_type {
enum class ElementType {
  Tri3,
  Quad4,
  Tri6,
  Quad9,
  Tet4,
  Tet10,
  Hex8,
  Hex27,
  Line2,
  Line3,
  Quad8,  // serendipity: read from meshes and used as contact faces, not assembled
  Hex20   // serendipity: read from meshes, not assembled
};
}  // namespace element_type
using element_type::ElementType;

// Bounds for fixed-size per-element arrays inside kernels.
constexpr int kMaxElementNodes = 27;
constexpr int kMaxGaussPoints = 27;
constexpr int kMaxDim = 3;

struct ElementInfo {
  int dim;             // reference dimension; the spatial dimension of a mesh of solids
  bool simplex;        // Lagrange on the simplex, else tensor product on [-1, 1]^dim
  int order;           // polynomial order, 1 or 2
  int nodes;           // nodes per element
  int corners;         // vertices
  int gaussPoints;     // points of the rule above (0: not assembled)
  ElementType face;    // the type of the (dim - 1)-dimensional faces (edges in 2D)
  ElementType linear;  // the order-1 element on the same corners
  bool complete;       // complete Lagrange: shape functions and Gauss rule here; false for the
                       // serendipity Quad8 and Hex20, which the assembly rejects
  bool meshBody;       // the mesh reader takes it as a body (an element of the mesh's dimension)
  int gmshType;        // Gmsh's element type code (MSH_LIN_2 = 1, MSH_TRI_3 = 2, ...)
  int vtkType;         // VTK's cell type (VTK_LINE = 3, VTK_TRIANGLE = 5, ...)
};

KOKKOS_INLINE_FUNCTION ElementInfo elementInfo(ElementType t) {
  using T = ElementType;
  // clang-format off
  //                    dim simplex order nodes corners Gauss face      linear    complete body  Gmsh VTK
  switch (t) {
    case T::Line2: return {1, false, 1,  2, 2,  2, T::Line2, T::Line2, true,  false,  1,  3};  // VTK_LINE
    case T::Line3: return {1, false, 2,  3, 2,  3, T::Line2, T::Line2, true,  false,  8, 21};  // VTK_QUADRATIC_EDGE
    case T::Tri3:  return {2, true,  1,  3, 3,  1, T::Line2, T::Tri3,  true,  true,   2,  5};  // VTK_TRIANGLE
    case T::Tri6:  return {2, true,  2,  6, 3,  3, T::Line3, T::Tri3,  true,  true,   9, 22};  // VTK_QUADRATIC_TRIANGLE
    case T::Quad4: return {2, false, 1,  4, 4,  4, T::Line2, T::Quad4, true,  true,   3,  9};  // VTK_QUAD
    case T::Quad8: return {2, false, 2,  8, 4,  0, T::Line3, T::Quad4, false, false, 16, 23};  // VTK_QUADRATIC_QUAD
    case T::Quad9: return {2, false, 2,  9, 4,  9, T::Line3, T::Quad4, true,  true,  10, 28};  // VTK_BIQUADRATIC_QUAD
    case T::Tet4:  return {3, true,  1,  4, 4,  1, T::Tri3,  T::Tet4,  true,  true,   4, 10};  // VTK_TETRA
    case T::Tet10: return {3, true,  2, 10, 4,  4, T::Tri6,  T::Tet4,  true,  true,  11, 24};  // VTK_QUADRATIC_TETRA
    case T::Hex8:  return {3, false, 1,  8, 8,  8, T::Quad4, T::Hex8,  true,  true,   5, 12};  // VTK_HEXAHEDRON
    case T::Hex20: return {3, false, 2, 20, 8,  0, T::Quad8, T::Hex8,  false, true,  17, 25};  // VTK_QUADRATIC_HEXAHEDRON
    case T::Hex27: return {3, false, 2, 27, 8, 27, T::Quad9, T::Hex8,  true,  true,  12, 29};  // VTK_TRIQUADRATIC_HEXAHEDRON
  }
  // clang-format on
  return {0, false, 0, 0, 0, 0, t, t, false, false, 0, 0};
}

KOKKOS_INLINE_FUNCTION int spatialDimension(ElementType t) {
  return elementInfo(t).dim;
}
KOKKOS_INLINE_FUNCTION int nodesPerElement(ElementType t) {
  return elementInfo(t).nodes;
}
KOKKOS_INLINE_FUNCTION int cornersPerElement(ElementType t) {
  return elementInfo(t).corners;
}
KOKKOS_INLINE_FUNCTION bool isQuadratic(ElementType t) {
  return elementInfo(t).order == 2;
}
KOKKOS_INLINE_FUNCTION int numGaussPoints(ElementType t) {
  return elementInfo(t).gaussPoints;
}
KOKKOS_INLINE_FUNCTION ElementType faceType(ElementType t) {
  return elementInfo(t).face;
}
// Nodes on one element face (one edge in 2D: 2, or 3 -- end, end, middle -- when quadratic).
KOKKOS_INLINE_FUNCTION int nodesPerFace(ElementType t) {
  return nodesPerElement(faceType(t));
}
KOKKOS_INLINE_FUNCTION int nodesPerEdge(ElementType t) {
  return isQuadratic(t) ? 3 : 2;
}
// Faces per element: dim + 1 for simplices, 2 dim for tensor products (the ends of a line).
KOKKOS_INLINE_FUNCTION int facesPerElement(ElementType t) {
  const ElementInfo i = elementInfo(t);
  return i.simplex ? i.dim + 1 : 2 * i.dim;
}
inline int gmshType(ElementType t) {
  return elementInfo(t).gmshType;
}
inline int vtkType(ElementType t) {
  return elementInfo(t).vtkType;
}

// Host-side queries (plasticity_ElementTypes.cpp).

// Every type, in the catalogue's order: lines, then 2D, then 3D types, each family linear
// first. Lists of types in messages follow it.
const std::vector<ElementType>& allElementTypes();
// The short name ("Tri3", "Hex27"), used in the assembly's messages.
std::string elementTypeName(ElementType t);
// Gmsh's description ("3-node triangle", "27-node hexahedron"), used in the mesh's messages.
const char* elementLongName(ElementType t);
// The type of Gmsh's code `gmshType`; false when the catalogue has none.
bool elementTypeOfGmsh(int gmshType, ElementType& t);
// The type of VTK's cell type `vtkType`; false when the catalogue has none.
bool elementTypeOfVtk(int vtkType, ElementType& t);

// Local nodes of facet `facet` (0 .. facesPerElement - 1) of a 2D or 3D element, in the node
// order of an element of faceType(t), oriented so that the facet's normal by the right-hand rule
// (2D: the edge's direction turned clockwise) points out of the element. 2D: the edge from
// corner `facet` to corner `facet + 1` (cyclically), then its midside node. 3D: corners first
// (counter-clockwise seen from outside), then the midside nodes of the facet's edges in the
// facet's edge order, then the face centre (Hex27). Throws std::invalid_argument for a line,
// std::out_of_range for no such facet.
const std::vector<int>& facetNodes(ElementType t, int facet);
// A 2D element's nodes renumbered with the opposite orientation (clockwise <-> counter-clockwise):
// node k of the reversed element is node reversedNodes(t)[k] of the original (corners in reverse
// order from corner 0, the edge midpoints and the centre following their edges). Throws
// std::invalid_argument unless t is 2D.
const std::vector<int>& reversedNodes(ElementType t);
// vtkNodeOrder(t)[k] is the element's local node at VTK's position k: the identity but where
// VTK numbers the nodes otherwise than Gmsh (Tet10, Hex20, Hex27).
const std::vector<int>& vtkNodeOrder(ElementType t);

namespace detail {
// Corner pairs of the quadratic simplices' edge nodes, Gmsh order (triangles use the first 3).
KOKKOS_INLINE_FUNCTION void simplexEdge(int k, int& a, int& b) {
  const int e[6][2] = {{0, 1}, {1, 2}, {2, 0}, {3, 0}, {3, 2}, {3, 1}};
  a = e[k][0], b = e[k][1];
}
// Lattice index (0, 1, 2 for -1, 0, 1) of tensor-product node a in direction d: Gmsh's Hex27
// table, whose first 8 rows are Hex8, and whose z = -1 rows reduce to Quad9/Quad4.
KOKKOS_INLINE_FUNCTION int tensorIndex(const ElementInfo& info, int a, int d) {
  if (info.dim == 1) {
    const int line[3] = {0, 2, 1};
    return line[a];
  }
  if (info.dim == 2) {
    const int quad[9][2] = {{0, 0}, {2, 0}, {2, 2}, {0, 2}, {1, 0}, {2, 1}, {1, 2}, {0, 1}, {1, 1}};
    return quad[a][d];
  }
  const int hex[27][3] = {{0, 0, 0}, {2, 0, 0}, {2, 2, 0}, {0, 2, 0}, {0, 0, 2}, {2, 0, 2},
                          {2, 2, 2}, {0, 2, 2}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {2, 1, 0},
                          {2, 0, 1}, {1, 2, 0}, {2, 2, 1}, {0, 2, 1}, {1, 0, 2}, {0, 1, 2},
                          {2, 1, 2}, {1, 2, 2}, {1, 1, 0}, {1, 0, 1}, {0, 1, 1}, {2, 1, 1},
                          {1, 2, 1}, {1, 1, 2}, {1, 1, 1}};
  return hex[a][d];
}
}  // namespace detail

// Shape functions N[a] and their reference derivatives dN[a][j] = dN_a / dxi_j at xi (dim
// entries used).
KOKKOS_INLINE_FUNCTION void shapeFunctions(ElementType t, const double xi[], double N[],
                                           double dN[][kMaxDim]) {
  const ElementInfo info = elementInfo(t);
  const int dim = info.dim;
  if (info.simplex) {
    double L[kMaxDim + 1], dL[kMaxDim + 1][kMaxDim];
    L[0] = 1;
    for (int j = 0; j < dim; ++j) L[0] -= xi[j];
    for (int k = 0; k < dim; ++k) L[k + 1] = xi[k];
    for (int k = 0; k <= dim; ++k)
      for (int j = 0; j < dim; ++j) dL[k][j] = k == 0 ? -1.0 : (k == j + 1 ? 1.0 : 0.0);
    for (int a = 0; a < info.corners; ++a) {
      N[a] = info.order == 1 ? L[a] : L[a] * (2 * L[a] - 1);
      for (int j = 0; j < dim; ++j)
        dN[a][j] = info.order == 1 ? dL[a][j] : (4 * L[a] - 1) * dL[a][j];
    }
    for (int a = info.corners; a < info.nodes; ++a) {
      int p, q;
      detail::simplexEdge(a - info.corners, p, q);
      N[a] = 4 * L[p] * L[q];
      for (int j = 0; j < dim; ++j) dN[a][j] = 4 * (dL[p][j] * L[q] + L[p] * dL[q][j]);
    }
    return;
  }
  // 1D Lagrange polynomials at lattice points 0, 1, 2 (linear: -1, 1 as 0, 2).
  double l[kMaxDim][3], dl[kMaxDim][3];
  for (int d = 0; d < dim; ++d) {
    const double x = xi[d];
    if (info.order == 1) {
      l[d][0] = 0.5 * (1 - x), l[d][1] = 0, l[d][2] = 0.5 * (1 + x);
      dl[d][0] = -0.5, dl[d][1] = 0, dl[d][2] = 0.5;
    } else {
      l[d][0] = 0.5 * x * (x - 1), l[d][1] = 1 - x * x, l[d][2] = 0.5 * x * (x + 1);
      dl[d][0] = x - 0.5, dl[d][1] = -2 * x, dl[d][2] = x + 0.5;
    }
  }
  for (int a = 0; a < info.nodes; ++a) {
    int id[kMaxDim] = {0, 0, 0};
    for (int d = 0; d < dim; ++d) id[d] = detail::tensorIndex(info, a, d);
    N[a] = l[0][id[0]];
    for (int d = 1; d < dim; ++d) N[a] *= l[d][id[d]];
    for (int j = 0; j < dim; ++j) {
      dN[a][j] = j == 0 ? dl[0][id[0]] : l[0][id[0]];
      for (int d = 1; d < dim; ++d) dN[a][j] *= d == j ? dl[d][id[d]] : l[d][id[d]];
    }
  }
}

// Reference coordinates of node a (dim entries).
KOKKOS_INLINE_FUNCTION void referenceNode(ElementType t, int a, double xi[]) {
  const ElementInfo info = elementInfo(t);
  if (info.simplex) {
    for (int j = 0; j < info.dim; ++j) xi[j] = 0;
    if (a < info.corners) {
      if (a > 0) xi[a - 1] = 1;
      return;
    }
    int p, q;
    detail::simplexEdge(a - info.corners, p, q);
    if (p > 0) xi[p - 1] += 0.5;
    if (q > 0) xi[q - 1] += 0.5;
    return;
  }
  for (int d = 0; d < info.dim; ++d) xi[d] = detail::tensorIndex(info, a, d) - 1.0;
}

// Gauss point q of the element's rule: reference position and weight (the weights sum to the
// reference measure: 1/2 or 1/6 for simplices, 2^dim else). Tensor-product points run with xi
// fastest, from -1 towards +1.
KOKKOS_INLINE_FUNCTION void gaussPoint(ElementType t, int q, double xi[], double& w) {
  const ElementInfo info = elementInfo(t);
  const int dim = info.dim;
  if (info.simplex) {
    if (info.order == 1) {
      for (int j = 0; j < dim; ++j) xi[j] = 1.0 / (dim + 1);
      w = dim == 2 ? 0.5 : 1.0 / 6.0;
      return;
    }
    // dim + 1 points: all coordinates a except coordinate q - 1, which is b.
    const double a = dim == 2 ? 1.0 / 6.0 : 0.13819660112501051518;  // (5 - sqrt 5) / 20
    const double b = dim == 2 ? 2.0 / 3.0 : 0.58541019662496845446;  // (5 + 3 sqrt 5) / 20
    for (int j = 0; j < dim; ++j) xi[j] = q == j + 1 ? b : a;
    w = dim == 2 ? 1.0 / 6.0 : 1.0 / 24.0;
    return;
  }
  const double g2 = 0.57735026918962576451;  // 1/sqrt(3)
  const double g3 = 0.77459666924148337704;  // sqrt(3/5)
  const double p2[2] = {-g2, g2}, w2[2] = {1.0, 1.0};
  const double p3[3] = {-g3, 0.0, g3}, w3[3] = {5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0};
  const int n = info.order + 1;
  int r = q;
  for (int d = 0; d < dim; ++d) {
    const int k = r % n;
    r /= n;
    xi[d] = n == 2 ? p2[k] : p3[k];
    const double wk = n == 2 ? w2[k] : w3[k];
    w = d == 0 ? wk : w * wk;
  }
}

// The physical derivatives dNdx[a][j] of shape functions whose reference derivatives are dN, for
// the element nodes x (npe nodes, dim coordinates each); returns the Jacobian determinant.
KOKKOS_INLINE_FUNCTION double mappedGradients(int npe, int dim, const double* x,
                                              const double dN[][kMaxDim], double dNdx[][kMaxDim]) {
  double J[kMaxDim][kMaxDim] = {};  // J[i][j] = d x_i / d xi_j
  for (int a = 0; a < npe; ++a)
    for (int i = 0; i < dim; ++i)
      for (int j = 0; j < dim; ++j) J[i][j] += x[dim * a + i] * dN[a][j];
  double det, inv[kMaxDim][kMaxDim];
  if (dim == 1) {
    det = J[0][0];
    inv[0][0] = 1 / det;
  } else if (dim == 2) {
    det = J[0][0] * J[1][1] - J[0][1] * J[1][0];
    inv[0][0] = J[1][1] / det, inv[0][1] = -J[0][1] / det;
    inv[1][0] = -J[1][0] / det, inv[1][1] = J[0][0] / det;
  } else {
    // Cofactors: inv = adj(J) / det.
    double c[3][3];
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) {
        const int i1 = (i + 1) % 3, i2 = (i + 2) % 3, j1 = (j + 1) % 3, j2 = (j + 2) % 3;
        c[i][j] = J[i1][j1] * J[i2][j2] - J[i1][j2] * J[i2][j1];
      }
    det = J[0][0] * c[0][0] + J[0][1] * c[0][1] + J[0][2] * c[0][2];
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) inv[i][j] = c[j][i] / det;
  }
  for (int a = 0; a < npe; ++a)
    for (int j = 0; j < dim; ++j) {
      double s = 0;
      for (int k = 0; k < dim; ++k) s += dN[a][k] * inv[k][j];
      dNdx[a][j] = s;
    }
  return det;
}

// Shape functions and their physical derivatives dNdx[a][j] at xi for the element nodes x (dim
// coordinates per node, dim = spatialDimension(t)); returns the Jacobian determinant.
KOKKOS_INLINE_FUNCTION double physicalGradients(ElementType t, const double* x, const double xi[],
                                                double N[], double dNdx[][kMaxDim]) {
  const ElementInfo info = elementInfo(t);
  double dN[kMaxElementNodes][kMaxDim];
  shapeFunctions(t, xi, N, dN);
  return mappedGradients(info.nodes, info.dim, x, dN, dNdx);
}

}  // namespace plasticity
