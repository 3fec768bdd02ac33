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
// where no device is visible; with `required` (run_check.sh on a machine whose nvidia-smi lists
// a GPU) no device is an error instead.
inline bool visibleDevice(cudaDeviceProp& prop, bool required) {
  int devices = 0;
  const cudaError_t e = cudaGetDeviceCount(&devices);
  if (e != cudaSuccess || devices == 0) {
    const std::string why = e != cudaSuccess ? cudaGetErrorString(e) : "none visible";
    if (required) throw std::runtime_error("a CUDA device was required: " + why);
    std::printf("skipped: no GPU (no CUDA device: %s)\n", why.c_str());
    return false;
  }
  cuda(cudaGetDeviceProperties(&prop, 0), "cudaGetDeviceProperties");
  return true;
}

}  // namespace gpucheck
