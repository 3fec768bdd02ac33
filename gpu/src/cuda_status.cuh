#pragma once
// What the device checks share: CUDA errors as exceptions, and the device to run on.
#include <cuda_runtime.h>

#include <cstdio>
#include <stdexcept>
#include <string>

namespace gpucheck {

inline void cuda(cudaError_t e, const char* what) {
  if (e != cudaSuccess) throw std::runtime_error(std::string(what) + ": " + cudaGetErrorString(e));
}

// Device 0's properties, or false (and the line that makes run_check.sh and ctest report a skip)
// where no device is visible.
inline bool visibleDevice(cudaDeviceProp& prop) {
  int devices = 0;
  if (cudaGetDeviceCount(&devices) != cudaSuccess || devices == 0) {
    std::printf("skipped: no GPU (no CUDA device visible)\n");
    return false;
  }
  cuda(cudaGetDeviceProperties(&prop, 0), "cudaGetDeviceProperties");
  return true;
}

}  // namespace gpucheck
