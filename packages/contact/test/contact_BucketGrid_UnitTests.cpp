// The bucket grid's segment walk (contact_BucketGrid.hpp): on random boxes and segments in 2D
// and 3D, including segments along grid lines, through cell corners, partly or wholly outside
// the grid and of zero length, it returns every box that a point of the segment lies in (1,001
// points along it, tested against every box) and no box whose cell the segment does not come
// near.
#include <Teuchos_UnitTestHarness.hpp>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "contact_BucketGrid.hpp"

namespace {

// The boxes holding one of 1,001 points evenly spaced along the segment a..b: the boxes it
// meets, but for some it only grazes.
std::vector<int> boxesOnSampledSegment(int dim, const double* a, const double* b,
                                       const std::vector<double>& boxes) {
  std::vector<int> hit;
  const int numBoxes = static_cast<int>(boxes.size()) / (2 * dim);
  for (int box = 0; box < numBoxes; ++box) {
    const double* bx = &boxes[static_cast<std::size_t>(2 * dim) * box];
    for (int k = 0; k <= 1000; ++k) {
      bool inside = true;
      for (int c = 0; c < dim && inside; ++c) {
        const double p = a[c] + (b[c] - a[c]) * k / 1000.0;
        inside = p >= bx[c] && p <= bx[dim + c];
      }
      if (inside) {
        hit.push_back(box);
        break;
      }
    }
  }
  return hit;
}

// The distance from point p to the segment a..b.
double distanceToSegment(int dim, const double* a, const double* b, const double* p) {
  double dd = 0.0, dp = 0.0;
  for (int c = 0; c < dim; ++c) {
    dd += (b[c] - a[c]) * (b[c] - a[c]);
    dp += (p[c] - a[c]) * (b[c] - a[c]);
  }
  const double t = dd > 0.0 ? std::clamp(dp / dd, 0.0, 1.0) : 0.0;
  double s = 0.0;
  for (int c = 0; c < dim; ++c) {
    const double q = a[c] + t * (b[c] - a[c]) - p[c];
    s += q * q;
  }
  return std::sqrt(s);
}

TEUCHOS_UNIT_TEST(BucketGrid, SegmentWalkFindsEveryBoxTheSegmentMeets) {
  std::mt19937 gen(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int dim : {2, 3}) {
    // Small boxes (up to 0.06 wide) scattered over the unit square/cube; cells of 0.05.
    const int numBoxes = dim == 2 ? 400 : 2000;
    std::vector<double> boxes;
    for (int b = 0; b < numBoxes; ++b) {
      double lo[3], hi[3];
      for (int c = 0; c < dim; ++c) {
        lo[c] = u(gen);
        hi[c] = lo[c] + 0.06 * u(gen);
      }
      boxes.insert(boxes.end(), lo, lo + dim);
      boxes.insert(boxes.end(), hi, hi + dim);
    }
    const double h = 0.05;
    const contact::BucketGrid grid(dim, boxes, h);
    const double cellDiagonal = h * std::sqrt(static_cast<double>(dim));
    for (int s = 0; s < 120; ++s) {
      double a[3], b[3];
      for (int c = 0; c < dim; ++c) {
        a[c] = -0.3 + 1.6 * u(gen);
        b[c] = -0.3 + 1.6 * u(gen);
      }
      if (s % 4 == 1)  // along a grid line of the first axis, through cell corners
        for (int c = 1; c < dim; ++c) a[c] = b[c] = grid.cellSize() * std::floor(20 * u(gen));
      if (s % 4 == 2)  // a diagonal through cell corners
        for (int c = 0; c < dim; ++c) a[c] = -0.2, b[c] = 1.2;
      if (s % 4 == 3)  // zero length
        for (int c = 0; c < dim; ++c) b[c] = a[c];
      std::vector<int> found;
      grid.segmentCandidates(a, b, found);
      std::sort(found.begin(), found.end());
      found.erase(std::unique(found.begin(), found.end()), found.end());
      for (int box : boxesOnSampledSegment(dim, a, b, boxes))
        TEST_ASSERT(std::binary_search(found.begin(), found.end(), box));
      // Each box returned shares a cell with the segment: some point of it (its nearest
      // corner region) lies within a cell diagonal of the segment.
      for (int box : found) {
        const double* bx = &boxes[static_cast<std::size_t>(2 * dim) * box];
        double p[3];
        double nearest = 1e300;
        for (int corner = 0; corner < (1 << dim); ++corner) {
          for (int c = 0; c < dim; ++c) p[c] = (corner >> c) & 1 ? bx[dim + c] : bx[c];
          nearest = std::min(nearest, distanceToSegment(dim, a, b, p));
        }
        TEST_COMPARE(nearest, <=, cellDiagonal + 0.06 * std::sqrt(double(dim)) + 1e-12);
      }
    }
  }
}

TEUCHOS_UNIT_TEST(BucketGrid, SegmentWalkOfAnEmptyGrid) {
  const contact::BucketGrid grid(3, {}, 1.0);
  const double a[3] = {0, 0, 0}, b[3] = {1, 1, 1};
  std::vector<int> found;
  grid.segmentCandidates(a, b, found);
  TEST_ASSERT(found.empty());
}

}  // namespace
