#include "contact_BucketGrid.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <stdexcept>

namespace contact {

bool clipSegmentToBox(int dim, const double* a, const double* b, const double* lo, const double* hi,
                      double& t0, double& t1) {
  t0 = 0.0, t1 = 1.0;
  for (int c = 0; c < dim; ++c) {
    const double d = b[c] - a[c];
    if (d == 0.0) {
      if (a[c] < lo[c] || a[c] > hi[c]) return false;
      continue;
    }
    double s0 = (lo[c] - a[c]) / d, s1 = (hi[c] - a[c]) / d;
    if (s0 > s1) std::swap(s0, s1);
    t0 = std::max(t0, s0), t1 = std::min(t1, s1);
    if (t0 > t1) return false;
  }
  return true;
}

BucketGrid::BucketGrid(int dim, const std::vector<double>& boxes, double cellSize)
    : dim_(dim), h_(cellSize) {
  if (dim != 2 && dim != 3) throw std::invalid_argument("BucketGrid: dimension must be 2 or 3");
  if (!(cellSize > 0.0)) throw std::invalid_argument("BucketGrid: cellSize must be positive");
  const int numBoxes = static_cast<int>(boxes.size() / (2 * dim));
  std::array<double, 3> hi{};
  for (int i = 0; i < dim; ++i) {
    lo_[i] = std::numeric_limits<double>::infinity();
    hi[i] = -lo_[i];
  }
  for (int b = 0; b < numBoxes; ++b)
    for (int i = 0; i < dim; ++i) {
      lo_[i] = std::min(lo_[i], boxes[2 * dim * b + i]);
      hi[i] = std::max(hi[i], boxes[2 * dim * b + dim + i]);
    }
  // Bounded cell counts keep the packed cell key within range for any input scale.
  double extent = 0.0;
  for (int i = 0; i < dim; ++i) extent = std::max(extent, hi[i] - lo_[i]);
  h_ = std::max(h_, extent * (dim == 2 ? 1e-6 : 1e-5));
  for (int i = 0; i < dim; ++i)
    n_[i] = numBoxes > 0 ? static_cast<long long>(std::floor((hi[i] - lo_[i]) / h_)) + 1 : 1;
  for (int b = 0; b < numBoxes; ++b) {
    const double* box = &boxes[2 * dim * b];
    std::array<long long, 3> i0{0, 0, 0}, i1{0, 0, 0};
    for (int i = 0; i < dim; ++i) {
      i0[i] = index(box[i], i);
      i1[i] = index(box[dim + i], i);
    }
    for (long long i = i0[0]; i <= i1[0]; ++i)
      for (long long j = i0[1]; j <= i1[1]; ++j)
        for (long long k = i0[2]; k <= i1[2]; ++k) cells_[(i * n_[1] + j) * n_[2] + k].push_back(b);
  }
}

long long BucketGrid::index(double v, int axis) const {
  const long long i = static_cast<long long>(std::floor((v - lo_[axis]) / h_));
  return std::clamp(i, 0LL, n_[axis] - 1);
}

const std::vector<int>* BucketGrid::candidates(const double* x) const {
  long long key = 0;
  for (int i = 0; i < 3; ++i) {
    long long c = 0;
    if (i < dim_) {
      const double f = (x[i] - lo_[i]) / h_;
      if (!(f >= 0.0 && f < static_cast<double>(n_[i]))) return nullptr;
      c = index(x[i], i);
    }
    key = key * n_[i] + c;
  }
  const auto it = cells_.find(key);
  return it == cells_.end() ? nullptr : &it->second;
}

void BucketGrid::segmentCandidates(const double* a, const double* b, std::vector<int>& out) const {
  if (cells_.empty()) return;
  double hi[3], t0 = 0.0, t1 = 1.0, d[3] = {0.0, 0.0, 0.0};
  for (int i = 0; i < dim_; ++i) {
    hi[i] = lo_[i] + static_cast<double>(n_[i]) * h_;
    d[i] = b[i] - a[i];
  }
  if (!clipSegmentToBox(dim_, a, b, lo_.data(), hi, t0, t1)) return;
  // Amanatides and Woo's walk from the cell of a + t0 (b - a) to that of a + t1 (b - a).
  std::array<long long, 3> cell{0, 0, 0}, last{0, 0, 0}, step{0, 0, 0};
  std::array<double, 3> tNext{}, tDelta{};
  const double inf = std::numeric_limits<double>::infinity();
  for (int i = 0; i < 3; ++i) {
    tNext[i] = tDelta[i] = inf;
    if (i >= dim_) continue;
    cell[i] = index(a[i] + t0 * d[i], i);
    last[i] = index(a[i] + t1 * d[i], i);
    if (d[i] > 0.0) {
      step[i] = 1;
      tNext[i] = (lo_[i] + static_cast<double>(cell[i] + 1) * h_ - a[i]) / d[i];
      tDelta[i] = h_ / d[i];
    } else if (d[i] < 0.0) {
      step[i] = -1;
      tNext[i] = (lo_[i] + static_cast<double>(cell[i]) * h_ - a[i]) / d[i];
      tDelta[i] = -h_ / d[i];
    }
  }
  // At most one step per cell boundary crossed, so the walk ends even where rounding leaves the
  // last cell off the computed path.
  long long budget = 1;
  for (int i = 0; i < dim_; ++i) budget += std::llabs(last[i] - cell[i]) + 1;
  for (; budget > 0; --budget) {
    const auto it = cells_.find((cell[0] * n_[1] + cell[1]) * n_[2] + cell[2]);
    if (it != cells_.end()) out.insert(out.end(), it->second.begin(), it->second.end());
    if (cell == last) return;
    int axis = 0;
    for (int i = 1; i < dim_; ++i)
      if (tNext[i] < tNext[axis]) axis = i;
    if (tNext[axis] > t1) return;
    cell[axis] += step[axis];
    if (cell[axis] < 0 || cell[axis] >= n_[axis]) return;
    tNext[axis] += tDelta[axis];
  }
}

}  // namespace contact
