# Finds the project's third-party dependencies and wraps them in imported targets.
# Included by the build tree and, installed, by every package's CMake config, so that an
# application calling find_package(tfeti) gets the same dependencies the library was built with.
# Gmsh is not among them: only the contact package meshes (TfetiGmsh.cmake, included by the tree
# and by contact's config).
include_guard(GLOBAL)
include(CMakeFindDependencyMacro)
list(APPEND CMAKE_MODULE_PATH "${CMAKE_CURRENT_LIST_DIR}")

find_package(MPI REQUIRED COMPONENTS CXX)
find_package(Trilinos 13.2 REQUIRED
             COMPONENTS Teuchos Kokkos KokkosKernels Tpetra Belos Amesos2 Zoltan2)
find_package(METIS REQUIRED)
find_package(CHOLMOD REQUIRED)

if(NOT TARGET TfetiDeps::Trilinos)
  # Trilinos 13.2 exports plain library names, not usage-requirement targets: wrap them.
  add_library(TfetiDeps::Trilinos INTERFACE IMPORTED)
  set_target_properties(TfetiDeps::Trilinos PROPERTIES
    INTERFACE_INCLUDE_DIRECTORIES "${Trilinos_INCLUDE_DIRS};${Trilinos_TPL_INCLUDE_DIRS}"
    INTERFACE_LINK_LIBRARIES "${Trilinos_LIBRARIES};${Trilinos_TPL_LIBRARIES};MPI::MPI_CXX")
endif()
