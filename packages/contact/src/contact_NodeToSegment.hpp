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

#include "contact_GmshMesh.hpp"
#include "tfeti_Tearing.hpp"

namespace contact {

struct MasterSurface {
  int nodesPerSegment = 2;    // 2 or 3
  std::vector<int> segments;  // nodesPerSegment node ids per segment: a, b[, m]
  int numSegments() const {
    return nodesPerSegment > 0 ? static_cast<int>(segments.size()) / nodesPerSegment : 0;
  }
};

// What to do with a slave node whose closest point is the free end of the master surface (an
// end node with no neighbouring segment) while the node lies beyond that end, i.e. outside the
// master's extent.
enum class EndPolicy {
  Drop,  // no row: the node is not opposite the master
  Clamp  // a row at the end point with the end segment's normal: the master's tangent line is
         // extended past its end (the gap is the distance to that line, not to the end point)
};

struct NodeToSegmentOptions {
  // A slave node whose closest point on the master is farther than this gets no row, so every
  // row has |gap| <= searchRadius. Must be positive; keep it below half the master body's
  // thickness, or a deeply penetrated node may be projected onto the opposite face.
  double searchRadius = 0.0;
  EndPolicy endPolicy = EndPolicy::Drop;
  // A node is beyond a free end when its offset past the end along the end tangent exceeds this
  // fraction of the end segment's chord, so that a slave node exactly opposite the master's end
  // (matching meshes) keeps its row despite rounding.
  double endTolerance = 1e-8;
  // Bucket grid cell size; <= 0 chooses max(mean segment extent, searchRadius).
  double cellSize = 0.0;
  // Compare every slave node with every segment (reference for testing the grid search).
  bool bruteForce = false;
  int maxNewtonIterations = 30;
};

// One term of a row: coef times component `component` (0: x, 1: y) of the displacement of `node`.
struct NodeEntry {
  int node;
  int component;
  double coef;
};

enum class ProjectionKind {
  Interior,  // the closest point is inside a segment (or exactly opposite a free end)
  Corner,    // the closest point is a node shared by two segments
  End        // the node is beyond a free end, kept by EndPolicy::Clamp
};

struct NodeToSegmentRow {
  int slaveNode = -1;
  int segment = -1;  // index into MasterSurface::segments
  double xi = 0.0;   // parametric coordinate of the closest point on that segment
  ProjectionKind kind = ProjectionKind::Interior;
  std::array<double, 2> point{};   // closest point x_m (current geometry)
  std::array<double, 2> normal{};  // outward unit normal of the master used for the row
  double gap = 0.0;
  // The slave node's x, y, then each master node of the segment (segment order) x, y: always
  // 2 + 2 * nodesPerSegment entries, zero coefficients included, so the row's pattern depends
  // only on the segment.
  std::vector<NodeEntry> entries;
};

struct NodeToSegmentResult {
  std::vector<NodeToSegmentRow> rows;  // in the order of the slave node list
  long long candidatePairs = 0;        // (slave node, segment) closest-point evaluations
  long long allPairs = 0;              // slave nodes x segments, for comparison
  int beyondRadius = 0;                // slave nodes without a row: nothing within searchRadius
  int beyondEnd = 0;                   // slave nodes without a row: beyond a free end (Drop)
  long long gridCells = 0;             // occupied cells of the bucket grid
  double cellSize = 0.0;
};

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

// The row in the dual solver's form; dofOf(node, component) returns the (subdomain, local dof)
// that carries it (for a torn node any of its copies: gluing makes them equal).
tfeti::InequalityRow toInequalityRow(const NodeToSegmentRow& row,
                                     const std::function<std::pair<int, int>(int, int)>& dofOf);

}  // namespace contact
