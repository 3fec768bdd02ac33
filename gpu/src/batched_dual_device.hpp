#pragma once
// The explicit local dual operators F_s kept on a CUDA device and applied as one batched product
// y_s = F_s x_s (issue 29, docs/dual_operator.md). Plain C++, no CUDA header: tfeti's
// ExplicitDualOperator (FETI "Explicit device" = gpu, in a TFETI_ENABLE_CUDA build) and the
// standalone check (check_cuda.cu) use the same class, so the check run on a GPU machine tests
// the code the solver runs. The device code is in batched_dual_device.cu.
#include <cstddef>
#include <memory>
#include <string>
#include <vector>

namespace batched_dual {

// Whether a CUDA device is visible; if not, why (for the caller's error message).
bool deviceAvailable(std::string& why);

// How the device holds the blocks: full (every value, column-major), or the upper triangle by
// 32 × 32 tiles (batched_dual_tiles.hpp: about half the bytes, so about half the apply's
// memory traffic).
enum class Storage { Full, SymmetricTiles };

class DeviceBlocks {
 public:
  // rows[s] = m_s; values: the blocks full and column-major, block s at sum_{t<s} m_t^2.
  // Uploads them in the given storage; throws std::runtime_error (with CUDA's message) when the
  // device cannot hold them, or cannot give the tiles' kernel the shared memory that the largest
  // block needs.
  DeviceBlocks(const std::vector<int>& rows, const std::vector<double>& values,
               Storage storage = Storage::Full);
  ~DeviceBlocks();
  DeviceBlocks(const DeviceBlocks&) = delete;
  DeviceBlocks& operator=(const DeviceBlocks&) = delete;

  Storage storage() const;

  // Block s's values again (the same size, full column-major), after a reassembly.
  void update(std::size_t s, const double* values);

  // The stacked vectors in pinned host memory (vectorSize() values each, block s at
  // sum_{t<s} m_t): the caller gathers x into hostX(), apply() computes hostY(). One apply moves
  // x to the device, runs one kernel over every block and moves y back; it returns when y is
  // on the host.
  double* hostX();
  const double* hostY() const;
  void apply();

  std::size_t vectorSize() const;
  std::size_t blockBytes() const;  // the F_s on the device
  // Per apply: what the kernel streams (every block once, x read and y written) and what
  // crosses between host and device (x in, y out).
  double kernelBytes() const;
  double transferBytes() const;
  // Since construction: applies, the kernels' seconds (CUDA events) and the applies' seconds
  // with their transfers.
  long long applies() const;
  double kernelSeconds() const;
  double applySeconds() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace batched_dual
