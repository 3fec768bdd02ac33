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

// The part of the segment a + t (b - a), t in [0, 1], inside the box lo..hi (dim values each):
// false when they do not meet, else t0 <= t1 bound it.
bool clipSegmentToBox(int dim, const double* a, const double* b, const double* lo, const double* hi,
                      double& t0, double& t1);

class BucketGrid {
 public:
  // boxes: lo[0..dim-1], hi[0..dim-1] per box (2 dim values). cellSize > 0.
  BucketGrid(int dim, const std::vector<double>& boxes, double cellSize);

  // Boxes of the cell containing x (dim values), increasing; null when there are none.
  const std::vector<int>* candidates(const double* x) const;

  // Appends the boxes of every cell that the segment from a to b (dim values each) passes
  // through, cell by cell along it (a voxel walk, so no cell it crosses is skipped however long
  // it is); a box met in several cells is appended once per cell.
  void segmentCandidates(const double* a, const double* b, std::vector<int>& out) const;

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
