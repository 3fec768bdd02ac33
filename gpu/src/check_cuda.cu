// The standalone check and bench of the batched apply on a CUDA device (gpu/README.md): the
// blocks stay on the device, every apply moves the stacked dual vector in and out once.
//  - cuBLAS gemvStridedBatched (uniform block sizes), fp64 and fp32;
//  - a hand-written kernel, one thread block per subdomain (any block sizes), fp64 and fp32;
//  - batched_dual::DeviceBlocks, the class the main code applies its F_s with (FETI "Explicit
//    device" = gpu), fp64, with its update of a block;
// each checked against the CPU reference (fp64 to 1e-12, fp32 to 1e-5), with its time, the
// bytes it moves and the bandwidth achieved; and the same apply on the host's cores.
#include <cuda_runtime.h>
#ifndef TFETI_GPU_CHECK_NO_CUBLAS
#include <cublas_v2.h>
#endif

#include <algorithm>
#include <cstdio>
#include <exception>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include "batched_dual.hpp"
#include "batched_dual_device.hpp"
#include "batched_dual_kernel.cuh"
#include "batched_dual_tiles_kernel.cuh"
#include "cuda_status.cuh"

namespace {

using gpucheck::cuda;

#ifndef TFETI_GPU_CHECK_NO_CUBLAS
void cublas(cublasStatus_t s, const char* what) {
  if (s != CUBLAS_STATUS_SUCCESS)
    throw std::runtime_error(std::string(what) + ": cuBLAS status " + std::to_string(s));
}
#endif

template <class T>
struct Device {
  T *values = nullptr, *x = nullptr, *y = nullptr;
  ~Device() {
    cudaFree(values);
    cudaFree(x);
    cudaFree(y);
  }
};

#ifndef TFETI_GPU_CHECK_NO_CUBLAS
// cuBLAS's strided batched gemv (one block size), y_s = F_s x_s.
template <class T>
void gemvBatched(cublasHandle_t h, int m, int count, const T* A, const T* x, T* y) {
  const T one = 1, zero = 0;
  const long long stride = 1LL * m * m;
  if constexpr (std::is_same_v<T, double>)
    cublas(cublasDgemvStridedBatched(h, CUBLAS_OP_N, m, m, &one, A, m, stride, x, 1, m, &zero, y, 1,
                                     m, count),
           "cublasDgemvStridedBatched");
  else
    cublas(cublasSgemvStridedBatched(h, CUBLAS_OP_N, m, m, &one, A, m, stride, x, 1, m, &zero, y, 1,
                                     m, count),
           "cublasSgemvStridedBatched");
}
#else
using cublasHandle_t = void*;  // built without cuBLAS: the kernel and DeviceBlocks only
#endif

// Mean milliseconds of f() on the device over `repeats` after a warm-up.
template <class F>
double deviceMs(F&& f, int repeats) {
  f();
  cudaEvent_t a, b;
  cuda(cudaEventCreate(&a), "event");
  cuda(cudaEventCreate(&b), "event");
  cuda(cudaEventRecord(a), "record");
  for (int r = 0; r < repeats; ++r) f();
  cuda(cudaEventRecord(b), "record");
  cuda(cudaEventSynchronize(b), "synchronize");
  float ms = 0.0f;
  cuda(cudaEventElapsedTime(&ms, a, b), "elapsed");
  cudaEventDestroy(a);
  cudaEventDestroy(b);
  return ms / repeats;
}

// The symmetric tiles (batched_dual_tiles.hpp): about half the bytes of the full blocks.
template <class T>
void runTiles(const char* name, const gpucheck::Blocks& b, const std::vector<T>& hx,
              const std::vector<double>& ref, const gpucheck::Options& o,
              const long long* dVecOffset, const int* dRows, const T* dx, T* dy, double limit,
              bool& ok) {
  std::vector<std::int64_t> offset;
  const std::vector<T> tiles = batched_dual::packAllTiles<T>(b.rows, b.values, offset);
  const std::vector<long long> off(offset.begin(), offset.end());
  T* dTiles = nullptr;
  long long* dOff = nullptr;
  cuda(cudaMalloc(&dTiles, tiles.size() * sizeof(T)), "cudaMalloc tiles");
  cuda(cudaMalloc(&dOff, off.size() * sizeof(long long)), "cudaMalloc tile offsets");
  cuda(cudaMemcpy(dTiles, tiles.data(), tiles.size() * sizeof(T), cudaMemcpyHostToDevice),
       "upload tiles");
  cuda(cudaMemcpy(dOff, off.data(), off.size() * sizeof(long long), cudaMemcpyHostToDevice),
       "upload tile offsets");
  cuda(cudaMemset(dy, 0x7f, hx.size() * sizeof(T)), "cudaMemset y");
  const int count = static_cast<int>(b.rows.size());
  bool launched = true;
  const double ms = deviceMs(
      [&] {
        launched = batched_dual::launchBatchedApplyTiles<T>(count, b.maxRows, dTiles, dOff,
                                                            dVecOffset, dRows, dx, dy);
      },
      o.repeats);
  cuda(cudaGetLastError(), "tiles kernel launch");
  if (!launched) {
    std::printf("%-6s %-22s not run: a block of %d rows needs %zu bytes of shared memory\n", name,
                "kernel, symmetric tiles", b.maxRows, batched_dual::tilesSharedBytes<T>(b.maxRows));
  } else {
    std::vector<T> hy(hx.size());
    cuda(cudaMemcpy(hy.data(), dy, hy.size() * sizeof(T), cudaMemcpyDeviceToHost), "download");
    const double err = gpucheck::relativeError(hy, ref);
    const double bytes = static_cast<double>(tiles.size() + 2 * b.vecSize) * sizeof(T);
    ok = ok && err <= limit;
    std::printf(
        "%-6s %-22s %9.3f ms, %7.1f GB/s, error %.2e (limit %.0e)%s; %.0f %% of the "
        "full blocks' bytes\n",
        name, "kernel, symm. tiles", ms, bytes / (ms * 1e-3) / 1e9, err, limit,
        err <= limit ? "" : "  FAILED", 100.0 * bytes / gpucheck::bytesMoved(b, sizeof(T)));
  }
  cudaFree(dTiles);
  cudaFree(dOff);
}

template <class T>
bool run(const char* name, const gpucheck::Blocks& b, const std::vector<double>& x,
         const std::vector<double>& ref, const gpucheck::Options& o, cublasHandle_t h,
         const long long* dOffset, const long long* dVecOffset, const int* dRows, double limit) {
  const std::vector<T> hv(b.values.begin(), b.values.end()), hx(x.begin(), x.end());
  std::vector<T> hy(x.size());
  Device<T> d;
  cuda(cudaMalloc(&d.values, hv.size() * sizeof(T)), "cudaMalloc blocks");
  cuda(cudaMalloc(&d.x, hx.size() * sizeof(T)), "cudaMalloc x");
  cuda(cudaMalloc(&d.y, hx.size() * sizeof(T)), "cudaMalloc y");
  cuda(cudaMemcpy(d.values, hv.data(), hv.size() * sizeof(T), cudaMemcpyHostToDevice), "upload");
  cuda(cudaMemcpy(d.x, hx.data(), hx.size() * sizeof(T), cudaMemcpyHostToDevice), "upload x");
  const int count = static_cast<int>(b.rows.size());
  const double bytes = gpucheck::bytesMoved(b, sizeof(T));
  bool ok = true;
  const auto report = [&](const char* how, double ms) {
    cuda(cudaMemcpy(hy.data(), d.y, hy.size() * sizeof(T), cudaMemcpyDeviceToHost), "download");
    const double err = gpucheck::relativeError(hy, ref);
    ok = ok && err <= limit;
    std::printf("%-6s %-22s %9.3f ms, %7.1f GB/s, error %.2e (limit %.0e)%s\n", name, how, ms,
                bytes / (ms * 1e-3) / 1e9, err, limit, err <= limit ? "" : "  FAILED");
  };
  // y is overwritten with huge values before every measurement, so that an apply that writes
  // nothing cannot pass on the last one's result.
  const auto clearY = [&] { cuda(cudaMemset(d.y, 0x7f, hy.size() * sizeof(T)), "cudaMemset y"); };
  const auto kernel = [&] {
    batched_dual::launchBatchedApply<T>(count, b.maxRows, d.values, dOffset, dVecOffset, dRows, d.x,
                                        d.y);
  };
#ifndef TFETI_GPU_CHECK_NO_CUBLAS
  if (b.uniform()) {
    const int m = b.rows.front();
    clearY();
    report("cuBLAS gemvStrided",
           deviceMs([&] { gemvBatched<T>(h, m, count, d.values, d.x, d.y); }, o.repeats));
  }
#else
  (void)h;
#endif
  clearY();
  report("kernel", deviceMs(kernel, o.repeats));
  cuda(cudaGetLastError(), "kernel launch");
  runTiles<T>(name, b, hx, ref, o, dVecOffset, dRows, d.x, d.y, limit, ok);
  // The dual vector crossing to the device and back with every apply (pageable host memory).
  clearY();
  const double withTransfers = deviceMs(
      [&] {
        cudaMemcpy(d.x, hx.data(), hx.size() * sizeof(T), cudaMemcpyHostToDevice);
        kernel();
        cudaMemcpy(hy.data(), d.y, hy.size() * sizeof(T), cudaMemcpyDeviceToHost);
      },
      o.repeats);
  report("kernel + x, y transfer", withTransfers);
  return ok;
}

// The class the main code applies its F_s with (FETI "Explicit device" = gpu), in the given
// storage: the stacked x through its pinned buffer, every block by one kernel, y back; then a
// block replaced (update, as after a reassembly: the middle block doubled, so that its offsets
// in the blocks and in the vector matter) and applied again.
bool runDeviceBlocks(const gpucheck::Blocks& b, const std::vector<double>& x,
                     const std::vector<double>& ref, const gpucheck::Options& o,
                     batched_dual::Storage storage) {
  const std::string name =
      storage == batched_dual::Storage::Full ? "DeviceBlocks full" : "DeviceBlocks tiles";
  const auto label = [&](const char* what) { return name + " " + what; };
  batched_dual::DeviceBlocks dev(b.rows, b.values, storage);
  std::copy(x.begin(), x.end(), dev.hostX());
  for (int r = 0; r <= o.repeats; ++r) dev.apply();
  std::vector<double> y(dev.hostY(), dev.hostY() + dev.vectorSize());
  double err = gpucheck::relativeError(y, ref);
  const double n = static_cast<double>(dev.applies());
  const double kernelMs = 1e3 * dev.kernelSeconds() / n, applyMs = 1e3 * dev.applySeconds() / n;
  bool ok = err <= 1e-12;
  std::printf("fp64   %-26s %9.3f ms, %7.1f GB/s, error %.2e (limit 1e-12)%s; %.2f GiB\n",
              label("kernel").c_str(), kernelMs, dev.kernelBytes() / (kernelMs * 1e-3) / 1e9, err,
              ok ? "" : "  FAILED", dev.blockBytes() / 1073741824.0);
  std::printf("fp64   %-26s %9.3f ms (%.1f MB in and out per apply)\n", label("apply").c_str(),
              applyMs, dev.transferBytes() / 1e6);
  if (!b.rows.empty()) {
    const std::size_t k = b.rows.size() / 2, m = static_cast<std::size_t>(b.rows[k]);
    const auto first = b.values.begin() + b.offset[k];
    std::vector<double> twice(first, first + m * m);
    for (double& v : twice) v *= 2.0;
    dev.update(k, twice.data());
    dev.apply();
    std::vector<double> want = ref;
    for (std::size_t i = 0; i < m; ++i) want[b.vecOffset[k] + i] *= 2.0;
    y.assign(dev.hostY(), dev.hostY() + dev.vectorSize());
    err = gpucheck::relativeError(y, want);
    std::printf("fp64   %-26s error %.2e (limit 1e-12)%s\n", label("update").c_str(), err,
                err <= 1e-12 ? "" : "  FAILED");
    ok = ok && err <= 1e-12;
  }
  return ok;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    const gpucheck::Options o = gpucheck::parse(argc, argv);
    cudaDeviceProp prop{};
    if (!gpucheck::visibleDevice(prop, o.requireDevice)) return 0;
    std::printf("device: %s, %.1f GiB\n", prop.name, prop.totalGlobalMem / 1073741824.0);
    const gpucheck::Blocks b = gpucheck::load(o);
    gpucheck::describe(b);
    const std::vector<double> x = gpucheck::vectorFor(b);
    const std::vector<double> ref = gpucheck::reference(b, x);
    bool ok = gpucheck::hostCheck(b, x, ref, o);
    std::vector<long long> off(b.offset.begin(), b.offset.end()),
        voff(b.vecOffset.begin(), b.vecOffset.end());
    long long *dOff = nullptr, *dVoff = nullptr;
    int* dRows = nullptr;
    cuda(cudaMalloc(&dOff, off.size() * sizeof(long long)), "cudaMalloc");
    cuda(cudaMalloc(&dVoff, voff.size() * sizeof(long long)), "cudaMalloc");
    cuda(cudaMalloc(&dRows, b.rows.size() * sizeof(int)), "cudaMalloc");
    cuda(cudaMemcpy(dOff, off.data(), off.size() * sizeof(long long), cudaMemcpyHostToDevice), "");
    cuda(cudaMemcpy(dVoff, voff.data(), voff.size() * sizeof(long long), cudaMemcpyHostToDevice),
         "");
    cuda(cudaMemcpy(dRows, b.rows.data(), b.rows.size() * sizeof(int), cudaMemcpyHostToDevice), "");
    cublasHandle_t h = nullptr;
#ifndef TFETI_GPU_CHECK_NO_CUBLAS
    cublas(cublasCreate(&h), "cublasCreate");
#else
    std::printf("built without cuBLAS: no gemvStridedBatched line\n");
#endif
    ok = run<double>("fp64", b, x, ref, o, h, dOff, dVoff, dRows, 1e-12) && ok;
    ok = run<float>("fp32", b, x, ref, o, h, dOff, dVoff, dRows, 1e-5) && ok;
    ok = runDeviceBlocks(b, x, ref, o, batched_dual::Storage::Full) && ok;
    ok = runDeviceBlocks(b, x, ref, o, batched_dual::Storage::SymmetricTiles) && ok;
#ifndef TFETI_GPU_CHECK_NO_CUBLAS
    cublasDestroy(h);
#endif
    cudaFree(dOff);
    cudaFree(dVoff);
    cudaFree(dRows);
    std::printf("%s\n", ok ? "device check passed" : "device check FAILED");
    return ok ? 0 : 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 2;
  }
}
