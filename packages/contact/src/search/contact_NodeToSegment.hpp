#pragma once
// Node-to-segment contact in 2D (frictionless, small sliding per load step): the non-penetration
// rows between the nodes of a slave surface and the segments of a master surface.
//
// Conventions (all node ids are global node ids; the caller maps them to subdomain dofs):
//  - coords: x, y per node. A displacement u (x, y per node) may be given: the geometry is then
//    x + u, so the rows linearize about the current configuration.
//  - A master segment is a Gmsh line: 2 nodes (a, b) or 3 nodes (a, b, m), m the midside node.
//    Parametric coordinate xi in [-1, 1]: a at -1, b at +1, m at 0; shape functions
//    N_a = (1 - xi)/2, N_b = (1 + xi)/2 (linear), N_a = xi(xi - 1)/2, N_b = xi(xi + 1)/2,
//    N_m = 1 - xi^2 (quadratic).
//  - Orientation: the master body lies on the LEFT when walking from a to b, so the outward unit
//    normal is the tangent dx/dxi turned clockwise, n = (t_y, -t_x) / |t|. Element edges of a
//    counter-clockwise element (Gmsh's order for a surface with normal +z) have this orientation;
//    orientSegments* establish it for any segment list. Neighbouring segments must run head to
//    tail (the end b of one is the start a of the next); computeNodeToSegment checks this and
//    throws otherwise. A consistently reversed surface cannot be told apart from a correct one
//    without the body (the body may be inside or outside a closed loop): orient it with the body.
//  - Gap g = (x_s - x_m) . n, positive when open. The row is the linearized non-penetration
//    condition g + (u_s - sum_a N_a(xi) u_a) . n >= 0, stored as
//        -(n . u_s) + sum_a N_a(xi) (n . u_a) <= g,
//    i.e. tfeti::InequalityRow's sum coef * u <= gap with a multiplier >= 0 (the contact
//    pressure at the slave node).
#include <array>
#include <functional>
#include <utility>
#include <vector>

#include "contact_ContactRows.hpp"
#include "contact_GmshMesh.hpp"

namespace contact {

struct MasterSurface {
  int nodesPerSegment = 2;    // 2 or 3
  std::vector<int> segments;  // nodesPerSegment node ids per segment: a, b[, m]
  int numSegments() const {
    return nodesPerSegment > 0 ? static_cast<int>(segments.size()) / nodesPerSegment : 0;
  }
};

// The 2D instances of the common contact-row types (contact_ContactRows.hpp): segment = facet,
// xi[0] the segment's parametric coordinate, point and normal with z = 0, 2 + 2 * nodesPerSegment
// entries per row.
using NodeToSegmentOptions = ContactSearchOptions;
using NodeToSegmentRow = ContactRow;
using NodeToSegmentResult = ContactRowsResult;

// Closest-point projection of every slave node onto the master surface and its
// non-penetration row. Candidates come from a uniform bucket grid (hashed, so memory is
// proportional to the occupied cells) into which every segment's bounding box, enlarged by
// searchRadius, is inserted; a slave node is compared only with the segments of its cell.
//  - Linear segments: exact projection. Quadratic: Newton on d/dxi |x(xi) - x_s|^2 / 2 from
//    the chord projection (Gauss-Newton where the curvature term makes it indefinite), clamped
//    to [-1, 1], and compared with both end points.
//  - Corner (closest point a node shared by two segments): n = (x_s - x_m)/|x_s - x_m| when the
//    node is outside (on the side of the average of the two segments' normals), so the gap is
//    the distance and the row is insensitive to rigid rotations; otherwise (penetration, or the
//    node on the master node) n = the normalized average of the two segments' normals there.
//  - Free end: see EndPolicy.
//  - A segment having the slave node as one of its own nodes is skipped (a node is not
//    opposite its own surface).
// Throws std::invalid_argument for bad options, sizes or node ids, and for an inconsistently
// oriented or branching master surface (see findOrientationErrors).
NodeToSegmentResult computeNodeToSegment(const std::vector<double>& coords,
                                         const std::vector<int>& slaveNodes,
                                         const MasterSurface& master,
                                         const NodeToSegmentOptions& options,
                                         const std::vector<double>& displacement = {});

// Nodes where the surface is not a head-to-tail chain: two segments start or two end at the
// node (an inconsistently oriented neighbour), or more than two segments meet (a branch).
// Sorted, each node once; empty for a valid surface.
std::vector<int> findOrientationErrors(const MasterSurface& master);

// Flip (swap a and b) every segment that does not have interiorPoints[2k], [2k+1] strictly on its
// left: a point inside the body next to segment k (e.g. the centroid of the element having the
// edge). The side is taken with respect to the chord a-b. Returns the number of segments flipped.
int orientSegmentsByPoints(MasterSurface& master, const std::vector<double>& coords,
                           const std::vector<double>& interiorPoints);

// Same with one point for all segments: correct when the body is star-shaped with respect to it
// (e.g. a disc and its centre).
int orientSegmentsTowardPoint(MasterSurface& master, const std::vector<double>& coords, double x,
                              double y);

// Same with the body's elements: each segment must be an edge (same end nodes) of exactly one
// element of `connectivity` (numNodes(type) nodes per element, Gmsh order), whose corner
// centroid is the interior point. Throws std::invalid_argument for a segment that is no
// element's edge or the edge of two elements (not on the boundary).
int orientSegmentsByElements(MasterSurface& master, const std::vector<double>& coords,
                             ElementType type, const std::vector<int>& connectivity);

}  // namespace contact
