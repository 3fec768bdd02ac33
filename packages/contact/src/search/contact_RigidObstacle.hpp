#pragma once
// Rigid obstacles given analytically as master surfaces, one implementation for 2D and 3D: a
// half-space (bounded by a line in 2D, a plane in 3D) and a ball (a disc in 2D bounded by a
// circle, a solid sphere in 3D). The rows (contact_ContactRows.hpp) have coefficients on the
// slave node only and the exact gap on the configuration reference + displacement:
//   half-space: g = (x - p) . n, n the obstacle's outward unit normal, p a point on its plane;
//   ball:       g = |x - c| - R, n = (x - c) / |x - c|, c its centre, R its radius;
// row -(n . u_s) <= g (the linearized g + n . u_s >= 0), multiplier >= 0.
// With a gap direction d (a unit vector from the body towards the obstacle) the gap is measured
// along d instead, as a height function: g = t with x + t d on the obstacle's surface (the first
// point along d), and the row is d . u_s <= g (n = -d): the classical Signorini form, in which a
// node may only approach the obstacle along d (deal.II's step-41/42). A node whose line along d
// misses a ball gets no row (counted beyond the search radius).
// A moving obstacle (e.g. a tool pressed in by a prescribed displacement) is the same obstacle
// with its point or centre moved: the caller builds it for each configuration.
#include <array>
#include <string>
#include <vector>

#include "contact_ContactRows.hpp"

namespace contact {

struct RigidObstacle {
  enum class Shape { HalfSpace, Ball };
  int dim = 2;  // 2 or 3
  Shape shape = Shape::HalfSpace;
  std::array<double, 3> point{};   // half-space: a point on its boundary; ball: the centre
  std::array<double, 3> normal{};  // half-space: outward normal (any length > 0)
  double radius = 0.0;             // ball: > 0
  // Zero: the gap along the surface's normal (closest point). Otherwise the direction (any
  // length > 0) from the body towards the obstacle along which gaps are measured; for a
  // half-space it must point into it (against its outward normal).
  std::array<double, 3> gapDirection{};
  // Height function only: where on the obstacle the gap is read. true: at the node's reference
  // position X, so that the row is d . u <= h(X) - d . X, linear in u (the classical Signorini
  // form of small-strain codes, deal.II's step-41/42); false: at the current position X + u
  // (large displacements). The nonlinear driver sets it from the kinematics.
  bool heightAtReference = false;

  bool heightFunction() const {
    return gapDirection[0] != 0.0 || gapDirection[1] != 0.0 || gapDirection[2] != 0.0;
  }

  // Throws std::invalid_argument naming the obstacle's field that is wrong (dimension, a
  // non-finite value, a zero normal, a non-positive radius, a 2D obstacle with a z component).
  void validate() const;
};

// The shape from its name in an input: "plane" (3D) or "line" (2D) for a half-space, "sphere"
// (3D) or "circle" (2D) for a ball. Throws std::invalid_argument listing the valid names for the
// dimension.
RigidObstacle::Shape obstacleShapeFromName(const std::string& name, int dim);

// Rows of the slave nodes within options.searchRadius of the obstacle (|gap| <= radius; others
// counted in beyondRadius). coords and displacement: dim values per node. candidatePairs counts
// the nodes examined (every slave node: the obstacle is one analytic surface). Throws
// std::invalid_argument for bad options or sizes, and for a node at a ball's centre (no normal).
ContactRowsResult computeObstacleRows(const RigidObstacle& obstacle,
                                      const std::vector<double>& coords,
                                      const std::vector<int>& slaveNodes,
                                      const ContactSearchOptions& options,
                                      const std::vector<double>& displacement = {});

}  // namespace contact
