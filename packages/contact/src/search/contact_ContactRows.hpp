#pragma once
// The common form of frictionless contact rows in 2D and 3D, whatever the master surface is
// (segments of a 2D mesh, faces of a 3D mesh, a rigid obstacle given analytically), and the one
// interface the problem set-up calls to get them: ContactMaster::rows.
//
// A row is the linearized non-penetration condition of one slave node,
//     sum_k coef_k u_k <= gap,
// over (node, component) entries of the displacement u (node ids global, component 0..dim-1),
// i.e. tfeti::InequalityRow with a multiplier >= 0 (the contact force at the slave node):
//     -(n . u_s) + sum_a N_a (n . u_a) <= (x_s - x_m) . n,
// x_m the closest point of the master, n its outward unit normal, N_a the master facet's shape
// functions at x_m (no master terms for a rigid obstacle).
#include <array>
#include <functional>
#include <memory>
#include <utility>
#include <vector>

#include "tfeti_Tearing.hpp"

namespace contact {

// One term of a row: coef times component `component` (0: x, 1: y, 2: z) of the displacement of
// `node`.
struct NodeEntry {
  int node;
  int component;
  double coef;
};

enum class ProjectionKind {
  Interior,  // the closest point is inside a master facet (or exactly opposite a free end)
  Corner,    // a node shared by several facets (2D: two segments; 3D: faces around a vertex)
  End,       // the node is beyond a free end (edge in 3D), kept by EndPolicy::Clamp
  Edge       // 3D: a point inside an edge shared by two faces
};

// What to do with a slave node whose closest point is on the free boundary of the master surface
// (an end node with no neighbouring segment, an edge of one face only) while the node lies
// beyond it, i.e. outside the master's extent.
enum class EndPolicy {
  Drop,  // no row: the node is not opposite the master
  Clamp  // a row at the boundary point with that facet's normal: the master's tangent line
         // (plane) is extended past its end (the gap is the distance to it, not to the point)
};

// At a master corner (2D: two segments; 3D: a vertex or an edge) a slave node outside the
// normal cone gets the closest-point normal d / |d|, d = x_s - x_m, which keeps the row exactly
// invariant under rigid rotations. A node closer to the corner than this fraction of the facet's
// size takes the averaged normal instead: there d can be the solver's noise (a symmetry plane
// through the corner holds both nodes only to the tolerance), and d / |d| would point anywhere,
// e.g. along the plane, making the row nearly a combination of the symmetry rows so that its
// multiplier drifts. The gap changes by at most this fraction of the size at the switch.
inline constexpr double kCornerSnap = 1e-4;
// A node whose projection is within this distance (in the segment's parameter in [-1, 1]) of a
// vertex where two master segments meet is on the vertex (node-to-segment, 2D).
inline constexpr double kVertexSnap = 1e-6;

struct ContactSearchOptions {
  // A slave node whose closest point on the master is farther than this gets no row, so every
  // row has |gap| <= searchRadius. Must be positive; keep it below half the master body's
  // thickness, or a deeply penetrated node may be projected onto the opposite face.
  double searchRadius = 0.0;
  EndPolicy endPolicy = EndPolicy::Drop;
  // A node is beyond a free end (edge) when its offset past it, along the facet's outward
  // in-surface direction, exceeds this fraction of the facet's size, so that a slave node
  // exactly opposite the master's boundary (matching meshes) keeps its row despite rounding.
  double endTolerance = 1e-8;
  // Bucket grid cell size; <= 0 chooses max(mean facet extent, searchRadius).
  double cellSize = 0.0;
  // Compare every slave node with every facet (reference for testing the grid search).
  bool bruteForce = false;
  int maxNewtonIterations = 30;
};

struct ContactRow {
  int slaveNode = -1;
  int facet = -1;              // master segment (2D) or face (3D); -1 for a rigid obstacle
  std::array<double, 2> xi{};  // parametric coordinates of the closest point on that facet
                               // (segments: xi[0] in [-1, 1], xi[1] = 0)
  ProjectionKind kind = ProjectionKind::Interior;
  std::array<double, 3> point{};   // closest point x_m (current geometry; z = 0 in 2D)
  std::array<double, 3> normal{};  // outward unit normal of the master used for the row
  double gap = 0.0;
  // The slave node's components, then each master node of the facet (facet order): always
  // dim * (1 + nodes per facet) entries, zero coefficients included, so that the row's pattern
  // depends only on the facet. A rigid obstacle: the slave node's dim entries only. A mortar row
  // (contact_Mortar.hpp): the slave node, the other slave nodes of its dual basis' support, then
  // the master nodes of every facet it overlaps, dim components per node.
  std::vector<NodeEntry> entries;
  // Mortar rows: the integral of the node's dual basis function over the covered surface, the
  // measure that the multiplier (a nodal force) is divided by to give the pressure. 0 for a
  // collocation row, whose measure is the slave node's lumped share of the surface.
  double weight = 0.0;
};

struct ContactRowsResult {
  std::vector<ContactRow> rows;  // in the order of the slave node list
  long long candidatePairs = 0;  // (slave node, facet) closest-point evaluations
  long long allPairs = 0;        // slave nodes x facets, for comparison
  int beyondRadius = 0;          // slave nodes without a row: nothing within searchRadius
  int beyondEnd = 0;             // slave nodes without a row: beyond a free end (Drop)
  long long gridCells = 0;       // occupied cells of the bucket grid
  double cellSize = 0.0;
};

// Throws std::invalid_argument naming `who` for a non-positive search radius, a negative end
// tolerance or no Newton iteration.
void validateSearchOptions(const ContactSearchOptions& options, const char* who);

// The row in the dual solver's form; dofOf(node, component) returns the (subdomain, local dof)
// that carries it (for a torn node any of its copies: gluing makes them equal). Zero
// coefficients are dropped. Its key (tfeti::InequalityRow::key, the row's identity across
// contact updates, which carries the Newton loop's warm start over new rows) is
// kRowsPerSlaveNode * slaveNode: a slave node has rows in one pair only.
tfeti::InequalityRow toInequalityRow(const ContactRow& row,
                                     const std::function<std::pair<int, int>(int, int)>& dofOf);
inline constexpr long long kRowsPerSlaveNode = 4;  // the normal row and up to two tangential
// The key of the j-th (0, 1) tangential row beside the normal row `normal` (-1 without a key).
long long tangentialKey(const tfeti::InequalityRow& normal, std::size_t j);

// A master surface: what a contact pair's set-up holds to evaluate the rows on any
// configuration (the reference one, or reference + displacement in a nonlinear loop).
class ContactMaster {
 public:
  virtual ~ContactMaster() = default;
  virtual int dimension() const = 0;  // 2 or 3
  // Rows of the slave nodes on coords + displacement (dimension() values per node each;
  // displacement may be empty).
  virtual ContactRowsResult rows(const std::vector<double>& coords,
                                 const std::vector<int>& slaveNodes,
                                 const std::vector<double>& displacement = {}) const = 0;
  // The mesh nodes the rows' master entries refer to (empty for a rigid obstacle), sorted.
  virtual std::vector<int> masterNodes() const = 0;
};

}  // namespace contact
