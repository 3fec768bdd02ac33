#include "contact_BoxTree.hpp"

#include <algorithm>
#include <stdexcept>

namespace contact {

namespace {

constexpr int kLeafSize = 8;

// Whether the segment a + t (b - a), t in [0, 1], meets the box lo..hi (dim values each).
bool segmentMeetsBox(int dim, const double* a, const double* b, const double* lo,
                     const double* hi) {
  double t0 = 0.0, t1 = 1.0;
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

}  // namespace

BoxTree::BoxTree(int dim, const std::vector<double>& boxes) : dim_(dim), boxes_(boxes) {
  if (dim != 2 && dim != 3) throw std::invalid_argument("BoxTree: dimension must be 2 or 3");
  if (boxes.size() % (2 * dim) != 0)
    throw std::invalid_argument("BoxTree: the box list is not 2 dim values per box");
  const int n = static_cast<int>(boxes.size() / (2 * dim));
  order_.resize(n);
  for (int i = 0; i < n; ++i) order_[i] = i;
  nodes_.reserve(n > 0 ? 2 * (n / kLeafSize + 1) : 0);
  if (n > 0) build(0, n);
}

int BoxTree::build(int first, int count) {
  const int id = static_cast<int>(nodes_.size());
  nodes_.emplace_back();
  Node node;
  double clo[3], chi[3];  // bounds of the boxes' centres
  for (int c = 0; c < dim_; ++c) {
    node.lo[c] = clo[c] = 1e300;
    node.hi[c] = chi[c] = -1e300;
  }
  for (int k = first; k < first + count; ++k) {
    const double* b = &boxes_[static_cast<std::size_t>(2 * dim_) * order_[k]];
    for (int c = 0; c < dim_; ++c) {
      node.lo[c] = std::min(node.lo[c], b[c]);
      node.hi[c] = std::max(node.hi[c], b[dim_ + c]);
      const double centre = 0.5 * (b[c] + b[dim_ + c]);
      clo[c] = std::min(clo[c], centre);
      chi[c] = std::max(chi[c], centre);
    }
  }
  if (count <= kLeafSize) {
    node.first = first;
    node.count = count;
    nodes_[id] = node;
    return id;
  }
  // Halve the boxes at the median centre along the axis where the centres spread most.
  int axis = 0;
  for (int c = 1; c < dim_; ++c)
    if (chi[c] - clo[c] > chi[axis] - clo[axis]) axis = c;
  const int half = count / 2;
  auto centre = [&](int box) {
    const double* b = &boxes_[static_cast<std::size_t>(2 * dim_) * box];
    return b[axis] + b[dim_ + axis];
  };
  std::nth_element(order_.begin() + first, order_.begin() + first + half,
                   order_.begin() + first + count, [&](int x, int y) {
                     const double cx = centre(x), cy = centre(y);
                     return cx < cy || (cx == cy && x < y);
                   });
  node.left = build(first, half);
  node.right = build(first + half, count - half);
  nodes_[id] = node;
  return id;
}

void BoxTree::segmentQuery(const double* a, const double* b, double pad,
                           std::vector<int>& out) const {
  if (nodes_.empty()) return;
  const std::size_t start = out.size();
  // Depth-first; the median splits keep the depth below log2(n) + 1, so the stack never holds
  // more than that many nodes.
  int stack[128];
  int top = 0;
  stack[top++] = 0;
  double lo[3], hi[3];
  while (top > 0) {
    const Node& node = nodes_[stack[--top]];
    for (int c = 0; c < dim_; ++c) lo[c] = node.lo[c] - pad, hi[c] = node.hi[c] + pad;
    if (!segmentMeetsBox(dim_, a, b, lo, hi)) continue;
    if (node.left < 0) {
      for (int k = node.first; k < node.first + node.count; ++k) {
        const double* box = &boxes_[static_cast<std::size_t>(2 * dim_) * order_[k]];
        for (int c = 0; c < dim_; ++c) lo[c] = box[c] - pad, hi[c] = box[dim_ + c] + pad;
        if (segmentMeetsBox(dim_, a, b, lo, hi)) out.push_back(order_[k]);
      }
      continue;
    }
    stack[top++] = node.left;
    stack[top++] = node.right;
  }
  std::sort(out.begin() + static_cast<std::ptrdiff_t>(start), out.end());
}

}  // namespace contact
