#pragma once
// A bounding-volume hierarchy of axis-aligned boxes in 2D or 3D: the boxes that a segment meets,
// each box grown by a pad given with the query. The mortar search asks it, for each slave facet,
// for the master facets near the facet's normal through its centre; unlike a uniform grid, its
// cost does not depend on how much the facets' sizes vary over the surface.
#include <vector>

namespace contact {

class BoxTree {
 public:
  // boxes: lo[0..dim-1], hi[0..dim-1] per box.
  BoxTree(int dim, const std::vector<double>& boxes);

  // Appends, in increasing order, the boxes that the segment from a to b (dim values each)
  // meets once each box is grown by pad on every side.
  void segmentQuery(const double* a, const double* b, double pad, std::vector<int>& out) const;

  int numNodes() const { return static_cast<int>(nodes_.size()); }

 private:
  struct Node {
    double lo[3], hi[3];
    int left = -1, right = -1;  // children; -1 in a leaf
    int first = 0, count = 0;   // a leaf's boxes: order_[first .. first + count)
  };
  int build(int first, int count);
  int dim_;
  std::vector<double> boxes_;
  std::vector<int> order_;
  std::vector<Node> nodes_;
};

}  // namespace contact
