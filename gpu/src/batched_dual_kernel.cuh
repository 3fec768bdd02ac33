#pragma once
// The batched apply's kernel, y_s = F_s x_s for every block s: one thread block per block,
// thread i accumulating row i over the columns (column-major, so the threads of a warp read
// consecutive values of a column: one pass over the block streams it once). x_s is staged in
// shared memory where it fits (kSharedRows), read from global memory (cached) otherwise.
// Included by the standalone check (check_cuda.cu, fp64 and fp32) and the main code's device
// blocks (batched_dual_device.cu).
#include <cuda_runtime.h>

namespace batched_dual {

// Rows whose x_s fits the default 48 KiB of dynamic shared memory in fp64.
constexpr int kSharedRows = 6144;
constexpr int kThreads = 256;

template <class T, bool Shared>
__global__ void batchedApply(const T* values, const long long* offset, const long long* vecOffset,
                             const int* rows, const T* x, T* y) {
  const int s = blockIdx.x, m = rows[s];
  const T* a = values + offset[s];
  const T* xs = x + vecOffset[s];
  extern __shared__ unsigned char shared[];
  const T* xv = xs;
  if constexpr (Shared) {
    T* xsh = reinterpret_cast<T*>(shared);
    for (int j = threadIdx.x; j < m; j += blockDim.x) xsh[j] = xs[j];
    __syncthreads();
    xv = xsh;
  }
  for (int i = threadIdx.x; i < m; i += blockDim.x) {
    T acc = 0;
    for (int j = 0; j < m; ++j) acc += a[i + static_cast<long long>(j) * m] * xv[j];
    y[vecOffset[s] + i] = acc;
  }
}

// Launches the kernel over `count` blocks whose largest has maxRows rows.
template <class T>
void launchBatchedApply(int count, int maxRows, const T* values, const long long* offset,
                        const long long* vecOffset, const int* rows, const T* x, T* y,
                        cudaStream_t stream = 0) {
  if (count == 0) return;
  if (maxRows <= kSharedRows)
    batchedApply<T, true>
        <<<count, kThreads, maxRows * sizeof(T), stream>>>(values, offset, vecOffset, rows, x, y);
  else
    batchedApply<T, false><<<count, kThreads, 0, stream>>>(values, offset, vecOffset, rows, x, y);
}

}  // namespace batched_dual
