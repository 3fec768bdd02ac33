#pragma once
// The batched apply from the symmetric tiles (batched_dual_tiles.hpp): one thread block per
// subdomain, each warp taking every kTileWarps-th tile of it. A warp reads its tile as 32 columns
// of 32 consecutive values into shared memory (one padded 32 × 33 tile per warp), then lane r
// forms row r of T x_J and, off the diagonal, lane c column c of Tᵀ x_I, and adds them into the
// block's y_s in shared memory (atomics: tiles of one row or column meet in different warps).
// The I != J branch is uniform over the warp (one tile per warp), so the shuffles stay legal.
// y_s goes out once at the end. About half the bytes of the full blocks cross the memory bus.
#include <cuda_runtime.h>

#include "batched_dual_tiles.hpp"

namespace batched_dual {

constexpr int kTileWarps = 4;

// Shared memory of one thread block: y_s and one padded tile per warp.
template <class T>
constexpr std::size_t tilesSharedBytes(int maxRows) {
  return (static_cast<std::size_t>(maxRows) + kTileWarps * kTile * (kTile + 1)) * sizeof(T);
}

// The most dynamic shared memory a thread block may opt into on the current device (0 when
// CUDA cannot say).
inline std::size_t sharedBytesOptIn() {
  int device = 0, optIn = 0;
  if (cudaGetDevice(&device) != cudaSuccess ||
      cudaDeviceGetAttribute(&optIn, cudaDevAttrMaxSharedMemoryPerBlockOptin, device) !=
          cudaSuccess)
    return 0;
  return static_cast<std::size_t>(optIn);
}

template <class T>
__global__ void batchedApplyTiles(const T* tiles, const long long* tileOffset,
                                  const long long* vecOffset, const int* rows, const T* x, T* y) {
  const int s = blockIdx.x, m = rows[s];
  const T* blockTiles = tiles + tileOffset[s];
  const T* xs = x + vecOffset[s];
  extern __shared__ unsigned char shared[];
  T* ys = reinterpret_cast<T*>(shared);
  const int warp = threadIdx.x / kTile, lane = threadIdx.x % kTile;
  T* tile = ys + m + warp * kTile * (kTile + 1);  // tile[c * 33 + r] = T(r, c)
  for (int i = threadIdx.x; i < m; i += blockDim.x) ys[i] = T(0);
  __syncthreads();
  const long long count = tileCount(m);
  for (long long t = warp; t < count; t += kTileWarps) {
    int I = 0, J = 0;
    tileAt(t, I, J);
    const T* a = blockTiles + t * kTile * kTile;
    // The loads written before the stores, so that many are in flight at once. How many is the
    // compiler's: ptxas (CUDA 13.0, sm_90) gives the fp64 kernel 40 registers, fewer than 32
    // doubles take, so not all 32; the device check's bandwidth says whether it is enough.
    T column[kTile];
#pragma unroll
    for (int c = 0; c < kTile; ++c) column[c] = a[lane + kTile * c];
#pragma unroll
    for (int c = 0; c < kTile; ++c) tile[c * (kTile + 1) + lane] = column[c];
    __syncwarp();
    // Lane r holds x_I[r], lane c x_J[c] (zero outside the block, as the tile's padding is):
    // every lane reads them from the others by shuffles, no bounds inside the loops.
    const int row = kTile * I + lane, col = kTile * J + lane;
    const T xI = row < m ? xs[row] : T(0), xJ = col < m ? xs[col] : T(0);
    T acc = 0;
#pragma unroll
    for (int c = 0; c < kTile; ++c)
      acc += tile[c * (kTile + 1) + lane] * __shfl_sync(0xffffffffu, xJ, c);
    if (row < m) atomicAdd(&ys[row], acc);
    if (I != J) {
      T accT = 0;
#pragma unroll
      for (int r = 0; r < kTile; ++r)
        accT += tile[lane * (kTile + 1) + r] * __shfl_sync(0xffffffffu, xI, r);
      if (col < m) atomicAdd(&ys[col], accT);
    }
    __syncwarp();  // the tile is read by all lanes before the next one overwrites it
  }
  __syncthreads();
  for (int i = threadIdx.x; i < m; i += blockDim.x) y[vecOffset[s] + i] = ys[i];
}

// Launches the tiles' apply over `count` blocks whose largest has maxRows rows. Returns false
// (nothing launched) where the device cannot give a block the shared memory it needs.
template <class T>
bool launchBatchedApplyTiles(int count, int maxRows, const T* tiles, const long long* tileOffset,
                             const long long* vecOffset, const int* rows, const T* x, T* y,
                             cudaStream_t stream = 0) {
  if (count == 0) return true;
  const std::size_t bytes = tilesSharedBytes<T>(maxRows);
  if (bytes > 48 * 1024 &&
      (bytes > sharedBytesOptIn() ||
       cudaFuncSetAttribute(batchedApplyTiles<T>, cudaFuncAttributeMaxDynamicSharedMemorySize,
                            static_cast<int>(bytes)) != cudaSuccess))
    return false;
  batchedApplyTiles<T>
      <<<count, kTileWarps * kTile, bytes, stream>>>(tiles, tileOffset, vecOffset, rows, x, y);
  return true;
}

}  // namespace batched_dual
