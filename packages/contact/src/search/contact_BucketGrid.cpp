#include "contact_BucketGrid.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace contact {

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

}  // namespace contact
