#pragma once
// Node-to-face contact in 3D (frictionless, small sliding per load step): the non-penetration
// rows between the nodes of a slave surface and the faces of a master surface, in the common
// form of contact_ContactRows.hpp (3 + 3 * nodes-per-face entries per row).
//
// Conventions (node ids global; coords and displacement x, y, z per node):
//  - A master face is a Gmsh surface element: Tri3, Tri6 (reference triangle (0,0), (1,0),
//    (0,1)), Quad4, Quad8, Quad9 (reference square [-1,1]^2), nodes in Gmsh order.
//  - Orientation: x_xi x x_eta (the right-hand rule over the corners) points OUT of the master
//    body. masterFacesOfBoundary takes the faces from the body's elements in that orientation;
//    neighbouring faces must traverse their shared edge in opposite directions.
//  - Gap g = (x_s - x_m) . n with x_m the closest point of the master surface and n its outward
//    unit normal; row -(n . u_s) + sum_a N_a(xi, eta) (n . u_a) <= g.
#include <vector>

#include "contact_ContactRows.hpp"
#include "contact_GmshMesh.hpp"

namespace contact {

struct MasterFaceSurface {
  ElementType type = ElementType::Tri3;  // Tri3, Tri6, Quad4, Quad8 or Quad9
  std::vector<int> faces;                // numNodes(type) node ids per face, oriented outward
  int nodesPerFace() const { return numNodes(type); }
  int numFaces() const { return static_cast<int>(faces.size()) / nodesPerFace(); }
};

// Shape functions of a face type at (xi, eta) and their derivatives (each array numNodes(type)
// long; derivatives may be null).
void faceShapeFunctions(ElementType type, double xi, double eta, double* n, double* dNdXi,
                        double* dNdEta);

// Closest-point projection of every slave node onto the master faces and its row.
//  - Candidates come from a bucket grid of the faces' bounding boxes (the convex hull of their
//    Bezier control points, so curved quadratic faces are inside), enlarged by searchRadius.
//  - On a face: Newton on the parametric coordinates for min |x(xi, eta) - x_s|^2 / 2 (exact
//    second derivatives, Gauss-Newton where the Hessian is indefinite), projected onto the
//    reference face; when the minimum is on the face's boundary (or a corner is closer than the
//    interior minimum) every edge is searched by a 1D Newton on its curve and its ends.
//  - Edge shared by two faces, or a vertex shared by several (kinds Edge, Corner):
//    n = (x_s - x_m)/|x_s - x_m| when the node is outside (on the side of the normalized sum of
//    the faces' normals at x_m), so the gap is the distance; else that averaged normal.
//  - Free edge (of one face) with the node beyond it by more than endTolerance times the face's
//    size: options.endPolicy (Drop: no row; Clamp: kind End, the face's normal).
//  - A face having the slave node as one of its nodes is skipped.
// Throws std::invalid_argument for bad options, sizes, node ids, a face type that is not a
// surface element, a degenerate face, and an inconsistently oriented or non-manifold master
// (see findFaceOrientationErrors).
ContactRowsResult computeNodeToFace(const std::vector<double>& coords,
                                    const std::vector<int>& slaveNodes,
                                    const MasterFaceSurface& master,
                                    const ContactSearchOptions& options,
                                    const std::vector<double>& displacement = {});

// Corner nodes of edges that two faces traverse in the same direction (an inconsistently
// oriented neighbour) or that more than two faces share. Sorted, each node once.
std::vector<int> findFaceOrientationErrors(const MasterFaceSurface& master);

// The faces of a 3D mesh boundary, each taken from the body element it belongs to
// (elementFacetNodes), i.e. oriented out of that body. Throws std::invalid_argument naming the
// boundary and the file for a face on no body or faces of different types.
MasterFaceSurface masterFacesOfBoundary(const GmshMesh& mesh, const GmshBoundary& boundary);

}  // namespace contact
