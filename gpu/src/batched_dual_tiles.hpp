#pragma once
// Symmetric storage of the F_s for the device: the upper triangle by 32 × 32 tiles, so that an
// apply streams about half the bytes of the full blocks and every tile is read as whole columns
// of 32 consecutive values. Tile (I, J), I <= J, holds F_s(32 I + r, 32 J + c) at r + 32 c
// (column-major, zero outside the block); the tiles of a block follow column by column,
// t(I, J) = J (J + 1) / 2 + I. y_s = F_s x_s is then, over the tiles, y_I += T x_J and, off the
// diagonal, y_J += Tᵀ x_I.
// Plain C++ (the layout, the packing and a host apply in the same order as the device kernel,
// batched_dual_tiles_kernel.cuh), shared by the host and the device checks.
#include <cmath>
#include <cstdint>
#include <vector>

#ifdef __CUDACC__
#define BATCHED_DUAL_HD __host__ __device__
#else
#define BATCHED_DUAL_HD
#endif

namespace batched_dual {

constexpr int kTile = 32;

BATCHED_DUAL_HD inline int tilesPerSide(int m) {
  return (m + kTile - 1) / kTile;
}
BATCHED_DUAL_HD inline long long tileCount(int m) {
  const long long n = tilesPerSide(m);
  return n * (n + 1) / 2;
}

// The tile (I, J) at position t of a block.
BATCHED_DUAL_HD inline void tileAt(long long t, int& I, int& J) {
  long long j = static_cast<long long>((std::sqrt(8.0 * static_cast<double>(t) + 1.0) - 1.0) / 2.0);
  while ((j + 1) * (j + 2) / 2 <= t) ++j;  // the root's rounding, either way
  while (j * (j + 1) / 2 > t) --j;
  J = static_cast<int>(j);
  I = static_cast<int>(t - j * (j + 1) / 2);
}

// One block's tiles from its full column-major values (m × m): tileCount(m) · 1024 values.
template <class T>
void packTiles(const double* full, int m, T* tiles) {
  const long long count = tileCount(m);
  for (long long t = 0; t < count; ++t) {
    int I = 0, J = 0;
    tileAt(t, I, J);
    T* out = tiles + t * kTile * kTile;
    for (int c = 0; c < kTile; ++c)
      for (int r = 0; r < kTile; ++r) {
        const int i = kTile * I + r, j = kTile * J + c;
        out[r + kTile * c] =
            i < m && j < m ? static_cast<T>(full[i + static_cast<std::size_t>(j) * m]) : T(0);
      }
  }
}

// Every block's tiles, one block after the other; offset[s] is block s's first value.
template <class T>
std::vector<T> packAllTiles(const std::vector<int>& rows, const std::vector<double>& full,
                            std::vector<std::int64_t>& offset) {
  std::int64_t total = 0;
  offset.clear();
  for (int m : rows) {
    offset.push_back(total);
    total += tileCount(m) * kTile * kTile;
  }
  std::vector<T> tiles(static_cast<std::size_t>(total));
  std::size_t fullOffset = 0;
  for (std::size_t s = 0; s < rows.size(); ++s) {
    packTiles(full.data() + fullOffset, rows[s], tiles.data() + offset[s]);
    fullOffset += static_cast<std::size_t>(rows[s]) * rows[s];
  }
  return tiles;
}

// y = F x for one block from its tiles, tile by tile as the device kernel goes.
template <class T>
void tilesApply(const T* tiles, int m, const T* x, T* y) {
  for (int i = 0; i < m; ++i) y[i] = T(0);
  const long long count = tileCount(m);
  for (long long t = 0; t < count; ++t) {
    int I = 0, J = 0;
    tileAt(t, I, J);
    const T* a = tiles + t * kTile * kTile;
    for (int r = 0; r < kTile && kTile * I + r < m; ++r) {
      T acc = 0;
      for (int c = 0; c < kTile && kTile * J + c < m; ++c)
        acc += a[r + kTile * c] * x[kTile * J + c];
      y[kTile * I + r] += acc;
    }
    if (I == J) continue;
    for (int c = 0; c < kTile && kTile * J + c < m; ++c) {
      T acc = 0;
      for (int r = 0; r < kTile && kTile * I + r < m; ++r)
        acc += a[r + kTile * c] * x[kTile * I + r];
      y[kTile * J + c] += acc;
    }
  }
}

}  // namespace batched_dual
