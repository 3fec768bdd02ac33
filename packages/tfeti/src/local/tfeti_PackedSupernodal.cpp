// The packed supernodal solves (tfeti_PackedSupernodal.hpp). Within a supernode of nscol columns
// and nsrow rows (CHOLMOD's int version: super, pi, px and s are int arrays) the columns go in
// panels of b = min(kPanel, columns left); a panel starting at column j holds
//   its triangle, column by column, column k with rows k .. b - 1 (the diagonal first),
//   then the rows j + b .. nsrow - 1, each with its b values side by side.
#include "tfeti_PackedSupernodal.hpp"

#include <algorithm>
#include <stdexcept>

namespace tfeti {
namespace {

struct Supernode {
  int firstColumn, columns, rows;
  const int* rowIndices;  // the supernode's rows; the first `columns` are its own columns
};

Supernode supernode(const cholmod_factor& L, std::size_t s) {
  const int* super = static_cast<const int*>(L.super);
  const int* pi = static_cast<const int*>(L.pi);
  return {super[s], super[s + 1] - super[s], pi[s + 1] - pi[s],
          static_cast<const int*>(L.s) + pi[s]};
}

// Values of a panel of b columns starting at column j of a supernode of `rows` rows.
std::size_t panelSize(int rows, int j, int b) {
  return static_cast<std::size_t>(b) * (b + 1) / 2 + static_cast<std::size_t>(rows - j - b) * b;
}

// Start of column k of a b-column panel's triangle.
int triangleColumn(int k, int b) {
  return k * b - k * (k - 1) / 2;
}

// visit(i, c) for the entries (row i, column c) of supernode sn in the packed order, the layout
// both directions of the repacking follow.
template <class Visit>
void forEachPackedEntry(const Supernode& sn, Visit&& visit) {
  for (int j = 0; j < sn.columns; j += kPanel) {
    const int b = std::min(kPanel, sn.columns - j);
    for (int k = 0; k < b; ++k)
      for (int r = k; r < b; ++r) visit(j + r, j + k);
    for (int i = j + b; i < sn.rows; ++i)
      for (int k = 0; k < b; ++k) visit(i, j + k);
  }
}

}  // namespace

PackedLayout packedLayout(const cholmod_factor& L) {
  if (!L.is_super) throw std::logic_error("packedLayout: the factor is not supernodal");
  PackedLayout layout;
  layout.offsets.assign(L.nsuper + 1, 0);
  for (std::size_t s = 0; s < L.nsuper; ++s) {
    const Supernode sn = supernode(L, s);
    const std::size_t c = static_cast<std::size_t>(sn.columns);
    layout.offsets[s + 1] =
        layout.offsets[s] + c * static_cast<std::size_t>(sn.rows) - c * (c - 1) / 2;
    layout.maxRows = std::max(layout.maxRows, sn.rows);
  }
  return layout;
}

void packSupernodal(cholmod_factor& L, const PackedLayout& layout, std::vector<double>& scratch) {
  double* x = static_cast<double*>(L.x);
  const int* px = static_cast<const int*>(L.px);
  // Packed supernode s starts at or before its column-major start and ends at or before the next
  // supernode's: going forward, each is written over itself and what was already packed.
  for (std::size_t s = 0; s < L.nsuper; ++s) {
    const Supernode sn = supernode(L, s);
    const std::size_t n = static_cast<std::size_t>(sn.columns) * sn.rows;
    scratch.assign(x + px[s], x + px[s] + n);
    double* out = x + layout.offsets[s];
    forEachPackedEntry(
        sn, [&](int i, int c) { *out++ = scratch[static_cast<std::size_t>(c) * sn.rows + i]; });
  }
}

void unpackSupernodal(cholmod_factor& L, const PackedLayout& layout, std::vector<double>& scratch) {
  double* x = static_cast<double*>(L.x);
  const int* px = static_cast<const int*>(L.px);
  // The reverse of packSupernodal, last supernode first. The upper triangles' padding is left
  // as it is: CHOLMOD's triangular kernels read the lower triangle only.
  for (std::size_t s = L.nsuper; s-- > 0;) {
    const Supernode sn = supernode(L, s);
    scratch.assign(x + layout.offsets[s], x + layout.offsets[s + 1]);
    double* block = x + px[s];
    const double* in = scratch.data();
    forEachPackedEntry(
        sn, [&](int i, int c) { block[static_cast<std::size_t>(c) * sn.rows + i] = *in++; });
  }
}

void packedForwardSolve(const cholmod_factor& L, const PackedLayout& layout, double* y, double* w) {
  const double* x = static_cast<const double*>(L.x);
  for (std::size_t s = 0; s < L.nsuper; ++s) {
    const Supernode sn = supernode(L, s);
    const double* __restrict a = x + layout.offsets[s];
    double* __restrict ws = w;
    // The supernode's own entries of y, and the updates it sends to the rows below it.
    for (int i = 0; i < sn.columns; ++i) ws[i] = y[sn.firstColumn + i];
    for (int i = sn.columns; i < sn.rows; ++i) ws[i] = 0.0;
    for (int j = 0; j < sn.columns; j += kPanel) {
      const int b = std::min(kPanel, sn.columns - j);
      const int below = sn.rows - j - b;
      double* __restrict wr = ws + j + b;
      if (b == 4) {
        const double x0 = ws[j] / a[0];
        const double x1 = (ws[j + 1] - a[1] * x0) / a[4];
        const double x2 = (ws[j + 2] - a[2] * x0 - a[5] * x1) / a[7];
        const double x3 = (ws[j + 3] - a[3] * x0 - a[6] * x1 - a[8] * x2) / a[9];
        ws[j] = x0, ws[j + 1] = x1, ws[j + 2] = x2, ws[j + 3] = x3;
        a += 10;
        for (int i = 0; i < below; ++i)
          wr[i] -= (a[4 * i] * x0 + a[4 * i + 1] * x1) + (a[4 * i + 2] * x2 + a[4 * i + 3] * x3);
        a += 4 * static_cast<std::size_t>(below);
        continue;
      }
      double xs[kPanel];
      for (int k = 0; k < b; ++k) {
        double v = ws[j + k];
        for (int c = 0; c < k; ++c) v -= a[triangleColumn(c, b) + (k - c)] * xs[c];
        xs[k] = v / a[triangleColumn(k, b)];
        ws[j + k] = xs[k];
      }
      a += b * (b + 1) / 2;
      for (int i = 0; i < below; ++i, a += b) {
        double v = 0.0;
        for (int k = 0; k < b; ++k) v += a[k] * xs[k];
        wr[i] -= v;
      }
    }
    for (int i = 0; i < sn.columns; ++i) y[sn.firstColumn + i] = ws[i];
    for (int i = sn.columns; i < sn.rows; ++i) y[sn.rowIndices[i]] += ws[i];
  }
}

void packedBackwardSolve(const cholmod_factor& L, const PackedLayout& layout, double* y,
                         double* w) {
  const double* x = static_cast<const double*>(L.x);
  for (std::size_t s = L.nsuper; s-- > 0;) {
    const Supernode sn = supernode(L, s);
    double* __restrict ws = w;
    // The solution at the rows below the supernode is final; its own columns are solved panel by
    // panel from the last, each panel's rows read forward.
    for (int i = sn.columns; i < sn.rows; ++i) ws[i] = y[sn.rowIndices[i]];
    const double* rhs = y + sn.firstColumn;
    std::size_t end = layout.offsets[s + 1];
    const int panels = (sn.columns + kPanel - 1) / kPanel;
    for (int q = panels - 1; q >= 0; --q) {
      const int j = q * kPanel, b = std::min(kPanel, sn.columns - j);
      const int below = sn.rows - j - b;
      end -= panelSize(sn.rows, j, b);
      const double* __restrict t = x + end;
      const double* __restrict a = t + b * (b + 1) / 2;
      const double* __restrict wr = ws + j + b;
      if (b == 4) {
        // Two rows per step: eight independent sums rather than four.
        double s0 = 0, s1 = 0, s2 = 0, s3 = 0, u0 = 0, u1 = 0, u2 = 0, u3 = 0;
        int i = 0;
        for (; i + 2 <= below; i += 2) {
          const double v = wr[i], v2 = wr[i + 1];
          const double* r = a + 4 * static_cast<std::size_t>(i);
          s0 += r[0] * v, s1 += r[1] * v, s2 += r[2] * v, s3 += r[3] * v;
          u0 += r[4] * v2, u1 += r[5] * v2, u2 += r[6] * v2, u3 += r[7] * v2;
        }
        for (; i < below; ++i) {
          const double v = wr[i];
          const double* r = a + 4 * static_cast<std::size_t>(i);
          s0 += r[0] * v, s1 += r[1] * v, s2 += r[2] * v, s3 += r[3] * v;
        }
        s0 += u0, s1 += u1, s2 += u2, s3 += u3;
        const double x3 = (rhs[j + 3] - s3) / t[9];
        const double x2 = (rhs[j + 2] - s2 - t[8] * x3) / t[7];
        const double x1 = (rhs[j + 1] - s1 - t[5] * x2 - t[6] * x3) / t[4];
        const double x0 = (rhs[j] - s0 - t[1] * x1 - t[2] * x2 - t[3] * x3) / t[0];
        ws[j] = x0, ws[j + 1] = x1, ws[j + 2] = x2, ws[j + 3] = x3;
        continue;
      }
      double sums[kPanel] = {};
      for (int i = 0; i < below; ++i)
        for (int k = 0; k < b; ++k) sums[k] += a[static_cast<std::size_t>(b) * i + k] * wr[i];
      for (int k = b - 1; k >= 0; --k) {
        const int tk = triangleColumn(k, b);
        double v = rhs[j + k] - sums[k];
        for (int r = k + 1; r < b; ++r) v -= t[tk + (r - k)] * ws[j + r];
        ws[j + k] = v / t[tk];
      }
    }
    for (int i = 0; i < sn.columns; ++i) y[sn.firstColumn + i] = ws[i];
  }
}

}  // namespace tfeti
