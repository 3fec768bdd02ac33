# The CUDA runtime for a tfeti built with TFETI_ENABLE_CUDA (FETI "Explicit device" = gpu,
# docs/dual_operator.md): included by the build tree and, installed, by tfeti's CMake config, so
# that an application linking tfeti::tfeti gets CUDA::cudart as the library was built with it.
include_guard(GLOBAL)
find_package(CUDAToolkit REQUIRED)
