#pragma once
// A hashed uniform grid of axis-aligned boxes in 2D or 3D (memory proportional to the occupied
// cells): every box is inserted into each cell it overlaps, so a point's cell lists every box
// that may contain it. The contact searches insert each master facet's bounding box enlarged by
// the search radius; a slave node is then compared only with the facets of its cell, which keeps
// the search near-linear in the number of surface nodes.
#include <array>
#include <unordered_map>
#include <vector>

namespace contact {

class BucketGrid {
 public:
  // boxes: lo[0..dim-1], hi[0..dim-1] per box (2 dim values). cellSize > 0.
  BucketGrid(int dim, const std::vector<double>& boxes, double cellSize);

  // Boxes of the cell containing x (dim values), increasing; null when there are none.
  const std::vector<int>* candidates(const double* x) const;

  long long occupiedCells() const { return static_cast<long long>(cells_.size()); }
  double cellSize() const { return h_; }

 private:
  long long index(double v, int axis) const;
  int dim_;
  double h_;
  std::array<double, 3> lo_{};
  std::array<long long, 3> n_{1, 1, 1};
  std::unordered_map<long long, std::vector<int>> cells_;
};

}  // namespace contact
