#include "batched_dual_device.hpp"

#include <cuda_runtime.h>

#include <algorithm>
#include <chrono>
#include <stdexcept>

#include "batched_dual_kernel.cuh"
#include "batched_dual_tiles_kernel.cuh"

namespace batched_dual {

namespace {
void check(cudaError_t e, const char* what) {
  if (e != cudaSuccess)
    throw std::runtime_error(std::string("CUDA: ") + what + ": " + cudaGetErrorString(e));
}

template <class T>
T* deviceCopy(const T* host, std::size_t n, const char* what) {
  T* d = nullptr;
  check(cudaMalloc(&d, std::max<std::size_t>(n, 1) * sizeof(T)), what);
  if (n > 0) check(cudaMemcpy(d, host, n * sizeof(T), cudaMemcpyHostToDevice), what);
  return d;
}
}  // namespace

bool deviceAvailable(std::string& why) {
  int devices = 0;
  const cudaError_t e = cudaGetDeviceCount(&devices);
  if (e != cudaSuccess) {
    why = std::string("no CUDA device (") + cudaGetErrorString(e) + ")";
    return false;
  }
  if (devices == 0) {
    why = "no CUDA device visible";
    return false;
  }
  return true;
}

struct DeviceBlocks::Impl {
  Storage storage = Storage::Full;
  std::vector<int> rows;
  std::vector<long long> offset, vecOffset;  // offset: into the full values or the tiles
  int maxRows = 0;
  std::size_t values = 0, vector = 0;  // values: what the device holds
  double *dValues = nullptr, *dX = nullptr, *dY = nullptr, *hX = nullptr, *hY = nullptr;
  long long *dOffset = nullptr, *dVecOffset = nullptr;
  int* dRows = nullptr;
  cudaEvent_t start = nullptr, stop = nullptr;
  long long applies = 0;
  double kernelSeconds = 0.0, applySeconds = 0.0;

  ~Impl() {
    cudaFree(dValues);
    cudaFree(dX);
    cudaFree(dY);
    cudaFree(dOffset);
    cudaFree(dVecOffset);
    cudaFree(dRows);
    cudaFreeHost(hX);
    cudaFreeHost(hY);
    if (start) cudaEventDestroy(start);
    if (stop) cudaEventDestroy(stop);
  }
};

DeviceBlocks::DeviceBlocks(const std::vector<int>& rows, const std::vector<double>& values,
                           Storage storage)
    : impl_(std::make_unique<Impl>()) {
  Impl& d = *impl_;
  d.storage = storage;
  d.rows = rows;
  for (int m : rows) {
    if (m < 0) throw std::invalid_argument("DeviceBlocks: a block with a negative size");
    d.offset.push_back(static_cast<long long>(d.values));
    d.vecOffset.push_back(static_cast<long long>(d.vector));
    d.values += static_cast<std::size_t>(m) * m;
    d.vector += m;
    d.maxRows = std::max(d.maxRows, m);
  }
  if (values.size() != d.values)
    throw std::invalid_argument("DeviceBlocks: " + std::to_string(values.size()) +
                                " values for blocks of " + std::to_string(d.values));
  if (storage == Storage::Full) {
    d.dValues = deviceCopy(values.data(), d.values, "the blocks F_s");
  } else {
    const std::size_t need = tilesSharedBytes<double>(d.maxRows), have = sharedBytesOptIn();
    if (need > have)
      throw std::runtime_error("DeviceBlocks: symmetric tiles of a block of " +
                               std::to_string(d.maxRows) + " rows need " + std::to_string(need) +
                               " bytes of shared memory per thread block; the device gives " +
                               std::to_string(have));
    // The offsets and the count become the tiles'.
    std::vector<std::int64_t> offset;
    const std::vector<double> tiles = packAllTiles<double>(rows, values, offset);
    d.offset.assign(offset.begin(), offset.end());
    d.values = tiles.size();
    d.dValues = deviceCopy(tiles.data(), tiles.size(), "the blocks F_s as symmetric tiles");
  }
  d.dOffset = deviceCopy(d.offset.data(), d.offset.size(), "block offsets");
  d.dVecOffset = deviceCopy(d.vecOffset.data(), d.vecOffset.size(), "vector offsets");
  d.dRows = deviceCopy(d.rows.data(), d.rows.size(), "block sizes");
  const std::size_t n = std::max<std::size_t>(d.vector, 1);
  check(cudaMalloc(&d.dX, n * sizeof(double)), "x");
  check(cudaMalloc(&d.dY, n * sizeof(double)), "y");
  check(cudaMallocHost(&d.hX, n * sizeof(double)), "pinned x");
  check(cudaMallocHost(&d.hY, n * sizeof(double)), "pinned y");
  check(cudaEventCreate(&d.start), "event");
  check(cudaEventCreate(&d.stop), "event");
}

DeviceBlocks::~DeviceBlocks() = default;

Storage DeviceBlocks::storage() const {
  return impl_->storage;
}

void DeviceBlocks::update(std::size_t s, const double* values) {
  const Impl& d = *impl_;
  const int m = d.rows.at(s);
  if (d.storage == Storage::Full) {
    check(cudaMemcpy(d.dValues + d.offset[s], values,
                     static_cast<std::size_t>(m) * m * sizeof(double), cudaMemcpyHostToDevice),
          "update of a block");
    return;
  }
  std::vector<double> tiles(static_cast<std::size_t>(tileCount(m)) * kTile * kTile);
  packTiles(values, m, tiles.data());
  check(cudaMemcpy(d.dValues + d.offset[s], tiles.data(), tiles.size() * sizeof(double),
                   cudaMemcpyHostToDevice),
        "update of a block");
}

double* DeviceBlocks::hostX() {
  return impl_->hX;
}
const double* DeviceBlocks::hostY() const {
  return impl_->hY;
}

void DeviceBlocks::apply() {
  Impl& d = *impl_;
  const auto t0 = std::chrono::steady_clock::now();
  const std::size_t bytes = d.vector * sizeof(double);
  check(cudaMemcpy(d.dX, d.hX, bytes, cudaMemcpyHostToDevice), "x to the device");
  check(cudaEventRecord(d.start), "event");
  const int count = static_cast<int>(d.rows.size());
  if (d.storage == Storage::Full)
    launchBatchedApply<double>(count, d.maxRows, d.dValues, d.dOffset, d.dVecOffset, d.dRows, d.dX,
                               d.dY);
  else if (!launchBatchedApplyTiles<double>(count, d.maxRows, d.dValues, d.dOffset, d.dVecOffset,
                                            d.dRows, d.dX, d.dY))
    throw std::runtime_error(
        "DeviceBlocks: the symmetric tiles' kernel could not get its shared "
        "memory");
  check(cudaGetLastError(), "the batched apply's launch");
  check(cudaEventRecord(d.stop), "event");
  check(cudaMemcpy(d.hY, d.dY, bytes, cudaMemcpyDeviceToHost), "y to the host");
  float ms = 0.0f;
  check(cudaEventElapsedTime(&ms, d.start, d.stop), "event time");
  d.kernelSeconds += 1e-3 * ms;
  d.applySeconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  ++d.applies;
}

std::size_t DeviceBlocks::vectorSize() const {
  return impl_->vector;
}
std::size_t DeviceBlocks::blockBytes() const {
  return impl_->values * sizeof(double);
}
double DeviceBlocks::kernelBytes() const {
  return static_cast<double>(impl_->values + 2 * impl_->vector) * sizeof(double);
}
double DeviceBlocks::transferBytes() const {
  return 2.0 * static_cast<double>(impl_->vector) * sizeof(double);
}
long long DeviceBlocks::applies() const {
  return impl_->applies;
}
double DeviceBlocks::kernelSeconds() const {
  return impl_->kernelSeconds;
}
double DeviceBlocks::applySeconds() const {
  return impl_->applySeconds;
}

}  // namespace batched_dual
