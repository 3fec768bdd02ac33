// The box tree's segment query (contact_BoxTree.hpp), which finds the mortar search's
// candidates: on random boxes of mixed sizes in 2D and 3D and random segments (including ones
// along a coordinate axis, partly or wholly outside the boxes, and of zero length), with and
// without a pad, it returns every box grown by the pad that one of 1,001 points along the
// segment lies in, and only boxes that such points nearly reach: checked against every box,
// without the slab test the tree uses.
#include <Teuchos_UnitTestHarness.hpp>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "contact_BoxTree.hpp"

namespace {

// Whether one of 1,001 points evenly spaced along a..b lies in the box grown by pad.
bool sampledSegmentMeets(int dim, const double* a, const double* b, const double* box, double pad) {
  for (int k = 0; k <= 1000; ++k) {
    bool inside = true;
    for (int c = 0; c < dim && inside; ++c) {
      const double p = a[c] + (b[c] - a[c]) * k / 1000.0;
      inside = p >= box[c] - pad && p <= box[dim + c] + pad;
    }
    if (inside) return true;
  }
  return false;
}

TEUCHOS_UNIT_TEST(BoxTree, SegmentQueryAgainstEveryBox) {
  std::mt19937 gen(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int dim : {2, 3}) {
    // Boxes up to 0.01 wide, one in ten up to 0.2 (a graded mesh's large facets).
    const int numBoxes = dim == 2 ? 300 : 1500;
    std::vector<double> boxes;
    for (int i = 0; i < numBoxes; ++i) {
      const double size = i % 10 == 0 ? 0.2 : 0.01;
      double lo[3], hi[3];
      for (int c = 0; c < dim; ++c) {
        lo[c] = u(gen);
        hi[c] = lo[c] + size * u(gen);
      }
      boxes.insert(boxes.end(), lo, lo + dim);
      boxes.insert(boxes.end(), hi, hi + dim);
    }
    const contact::BoxTree tree(dim, boxes);
    TEST_COMPARE(tree.numNodes(), >, numBoxes / 8);
    int totalFound = 0;
    for (int s = 0; s < 120; ++s) {
      double a[3], b[3];
      for (int c = 0; c < dim; ++c) {
        a[c] = -0.3 + 1.6 * u(gen);
        b[c] = -0.3 + 1.6 * u(gen);
      }
      if (s % 4 == 1)  // along the first axis
        for (int c = 1; c < dim; ++c) b[c] = a[c];
      if (s % 4 == 3)  // zero length
        for (int c = 0; c < dim; ++c) b[c] = a[c];
      const double pad = s % 2 == 0 ? 0.0 : 0.02;
      std::vector<int> found = {-7};  // the query appends
      tree.segmentQuery(a, b, pad, found);
      TEST_EQUALITY(found.front(), -7);
      found.erase(found.begin());
      TEST_ASSERT(std::is_sorted(found.begin(), found.end()));
      TEST_ASSERT(std::adjacent_find(found.begin(), found.end()) == found.end());
      double length = 0.0;
      for (int c = 0; c < dim; ++c) length += (b[c] - a[c]) * (b[c] - a[c]);
      const double spacing = std::sqrt(length) / 1000.0;
      for (int i = 0; i < numBoxes; ++i) {
        const double* box = &boxes[static_cast<std::size_t>(2 * dim) * i];
        const bool returned = std::binary_search(found.begin(), found.end(), i);
        if (sampledSegmentMeets(dim, a, b, box, pad)) TEST_ASSERT(returned);
        if (returned) TEST_ASSERT(sampledSegmentMeets(dim, a, b, box, pad + spacing));
      }
      totalFound += static_cast<int>(found.size());
    }
    TEST_COMPARE(totalFound, >, 100);  // the segments do meet boxes
  }
}

TEUCHOS_UNIT_TEST(BoxTree, EmptyTreeAndBadInput) {
  const contact::BoxTree tree(3, {});
  const double a[3] = {0, 0, 0}, b[3] = {1, 1, 1};
  std::vector<int> found;
  tree.segmentQuery(a, b, 1.0, found);
  TEST_ASSERT(found.empty());
  TEST_THROW(contact::BoxTree(4, {}), std::invalid_argument);
  TEST_THROW(contact::BoxTree(2, {0.0, 0.0, 1.0}), std::invalid_argument);
}

}  // namespace
