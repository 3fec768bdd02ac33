#pragma once
// The numerical pieces of dual mortar contact (contact_Mortar.hpp), one dimension-generic set:
// facet shape functions, the multiplier space of a slave facet, the dual (biorthogonal) basis,
// polygon clipping on the auxiliary plane and quadrature on the clipped overlaps.
//
// A facet is a boundary element of the body: Line2, Line3 (2D; reference [-1, 1]) or Tri3, Tri6
// (reference triangle), Quad4, Quad8, Quad9 (reference square [-1, 1]^2) in 3D, nodes in Gmsh
// order. Its parametric dimension is the mesh's dimension minus one.
#include <array>
#include <vector>

#include "contact_GmshMesh.hpp"

namespace contact {

// Shape functions of a facet type at xi (1 or 2 coordinates) and their derivatives
// (dN[a * pdim + k] = dN_a / dxi_k; may be null). Throws for a type that is not a facet.
void facetShapeFunctions(ElementType type, const double* xi, double* N, double* dN);

// The parametric dimension of a facet type (1 for lines, 2 for surface elements).
int facetParametricDimension(ElementType type);

// The parametric centre of a facet type.
std::array<double, 2> facetCentre(ElementType type);

// The multipliers of a slave facet live on its first `count` nodes (local indices into the
// facet), with the dual basis of the space's functions (multiplierShapeFunctions):
//  - Line2, Line3, Tri3, Quad4, Quad9: every node, the facet's own shape functions (each
//    integrates to a positive share of the facet);
//  - Tri6, Quad8: every node, the quadratic functions modified by `alpha` (Popp, Wohlmuth, Gee
//    and Wall 2012): a corner's function gains alpha times its two neighbouring midside
//    functions, a midside function is scaled by 1 - 2 alpha. The plain quadratic corner
//    functions integrate to zero (Tri6) or a negative value (Quad8) over the facet, so no dual
//    basis of them exists; with alpha = 1/5 every share is positive (Tri6: 2/15 and 1/5 of the
//    facet, Quad8: 1/20 and 1/5), the span is still the quadratic space, and the multipliers
//    resolve the contact zone's edge at the midside nodes too.
struct MultiplierSpace {
  ElementType type;
  int count;
  double alpha = 0.0;
};
MultiplierSpace multiplierSpace(ElementType slaveFacetType);

// The multiplier space's functions at xi (count values).
void multiplierShapeFunctions(const MultiplierSpace& space, const double* xi, double* N);

// The dual basis on a domain given by quadrature: points q with weights w[q] and the n
// multiplier-space functions N[q * n + a] there. Returns A (n x n, row-major) such that
// phi_j = sum_b A[j n + b] N_b satisfies  sum_q w phi_j N_b = delta_jb sum_q w N_j, i.e.
// A = D M^{-1} with M the mass matrix and D its row sums' diagonal (the shares of the domain).
// Returns an empty vector when M is singular to rounding (a domain of (nearly) zero measure).
std::vector<double> dualBasisCoefficients(int n, const std::vector<double>& w,
                                          const std::vector<double>& N);

// A polygon in the plane, counter-clockwise.
using Polygon = std::vector<std::array<double, 2>>;

// Signed area (positive counter-clockwise).
double polygonArea(const Polygon& p);

// The part of `subject` inside the convex, counter-clockwise polygon `clip` (Sutherland-Hodgman).
// Vertices closer than `tolerance` to the previous one are merged; a result with fewer than three
// vertices is empty (a degenerate overlap: a shared edge or vertex only).
Polygon clipPolygon(const Polygon& subject, const Polygon& clip, double tolerance);

// A quadrature rule on a region of the auxiliary plane (2D: an interval of the auxiliary line):
// points in its coordinates and weights summing to the region's measure.
struct PlaneQuadrature {
  std::vector<std::array<double, 2>> points;
  std::vector<double> weights;
};
// Gauss-Legendre with 5 points on [a, b] (exact for degree 9).
PlaneQuadrature intervalQuadrature(double a, double b);
// A convex polygon split into triangles from its first vertex, a 7-point rule (degree 5) on each.
PlaneQuadrature polygonQuadrature(const Polygon& p);
// A rule on the reference facet (for integrals over a whole facet): 5-point Gauss on lines, the
// 7-point rule on triangles, 4 x 4 Gauss on quadrilaterals; weights of the reference measure.
PlaneQuadrature referenceFacetQuadrature(ElementType type);

// A facet's geometry on a configuration x (dim values per mesh node).
struct FacetGeometry {
  int dim;
  ElementType type;
  const int* nodes;
  const std::vector<double>* x;
  int numNodes() const;
  // Position and tangents (dx/dxi_k, dim values each) at xi.
  void evaluate(const double* xi, double* pos, double* tangents) const;
  // The outward unit normal at xi: 2D the tangent turned clockwise, 3D x_xi x x_eta.
  std::array<double, 3> normal(const double* xi) const;
  // The measure element at xi: |x_xi| (2D) or |x_xi x x_eta| (3D).
  double jacobian(const double* xi) const;
};

// The auxiliary plane of a slave facet: through its centre, normal to it there; points are
// projected onto it along that normal.
struct AuxiliaryPlane {
  int dim = 3;
  std::array<double, 3> origin{}, normal{}, t1{}, t2{};
  explicit AuxiliaryPlane(const FacetGeometry& slave);
  // Plane coordinates of a point (its projection).
  std::array<double, 2> coordinates(const double* y) const;
  // Signed distance of a point from the plane along the normal.
  double height(const double* y) const;
  // The parametric coordinates of the facet point that projects onto plane point p (Newton from
  // the facet's centre). False when Newton does not converge.
  bool inverseMap(const FacetGeometry& f, const std::array<double, 2>& p, double* xi) const;
};

}  // namespace contact
