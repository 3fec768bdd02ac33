# tfeti_package(NAME <name> SOURCES ... DEPENDS ... [PACKAGE_DEPENDS ...] [CONFIG_INCLUDES ...]):
# a namespaced, installable library with an exported CMake config, so that an application
# outside the tree can call find_package(<name>) and link <name>::<name>. Static or shared as
# BUILD_SHARED_LIBS says. Its usage requirements: C++17, and in a TFETI_SANITIZE build the
# sanitizer flags (an application linking a sanitized library must compile and link with them).
# CONFIG_INCLUDES: files of the installed TfetiCommon directory the config includes (e.g.
# TfetiGmsh.cmake for a package that needs Gmsh).
include(CMakePackageConfigHelpers)
include(GNUInstallDirs)

function(tfeti_package)
  cmake_parse_arguments(P "" "NAME" "SOURCES;DEPENDS;PACKAGE_DEPENDS;CONFIG_INCLUDES" ${ARGN})
  add_library(${P_NAME} ${P_SOURCES})
  add_library(${P_NAME}::${P_NAME} ALIAS ${P_NAME})
  # Sources live in one sub-folder of src/ per area (each with a README.md); headers are
  # included by their file name alone (#include "tfeti_FetiSolver.hpp"), so every sub-folder is
  # on the include path, and they install flat into include/<name>/ as before.
  file(GLOB areas LIST_DIRECTORIES true ${CMAKE_CURRENT_SOURCE_DIR}/src/*)
  set(area_dirs ${CMAKE_CURRENT_SOURCE_DIR}/src)
  foreach(area ${areas})
    if(IS_DIRECTORY ${area})
      list(APPEND area_dirs ${area})
    endif()
  endforeach()
  foreach(dir ${area_dirs})
    target_include_directories(${P_NAME} PUBLIC $<BUILD_INTERFACE:${dir}>)
  endforeach()
  target_include_directories(${P_NAME} PUBLIC
    $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}/${P_NAME}>)
  target_link_libraries(${P_NAME} PUBLIC ${P_DEPENDS})
  target_compile_features(${P_NAME} PUBLIC cxx_std_17)
  if(TFETI_SANITIZE_FLAGS)
    target_compile_options(${P_NAME} INTERFACE ${TFETI_SANITIZE_FLAGS})
    target_link_options(${P_NAME} INTERFACE ${TFETI_SANITIZE_FLAGS})
  endif()
  # C++ sources only: nvcc takes no -Wall (a CUDA build's .cu sources, TFETI_ENABLE_CUDA).
  target_compile_options(${P_NAME} PRIVATE
                         $<$<COMPILE_LANGUAGE:CXX>:-Wall -Wextra -Wno-unused-parameter>)
  # No <name>_EXPORTS define for a shared build: no code uses it (every symbol is visible), and
  # without it a shared and a static build compile each object with the same command (both with
  # -fPIC), so that ccache serves one from the other (docs/shared_libraries.md).
  set_target_properties(${P_NAME} PROPERTIES EXPORT_NAME ${P_NAME} OUTPUT_NAME tfeti_${P_NAME}
                                             DEFINE_SYMBOL "")
  if(P_NAME STREQUAL "tfeti")
    set_target_properties(${P_NAME} PROPERTIES OUTPUT_NAME tfeti)
  endif()

  file(GLOB_RECURSE headers ${CMAKE_CURRENT_SOURCE_DIR}/src/*.hpp)
  install(FILES ${headers} DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/${P_NAME})
  install(TARGETS ${P_NAME} EXPORT ${P_NAME}Targets
          LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
          ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
          RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
  install(EXPORT ${P_NAME}Targets NAMESPACE ${P_NAME}::
          DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/${P_NAME})

  set(PACKAGE_DEPENDS "${P_PACKAGE_DEPENDS}")
  set(CONFIG_INCLUDES "${P_CONFIG_INCLUDES}")
  configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/PackageConfig.cmake.in
    ${CMAKE_CURRENT_BINARY_DIR}/${P_NAME}Config.cmake
    INSTALL_DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/${P_NAME})
  write_basic_package_version_file(${CMAKE_CURRENT_BINARY_DIR}/${P_NAME}ConfigVersion.cmake
    VERSION ${PROJECT_VERSION} COMPATIBILITY SameMajorVersion)
  install(FILES ${CMAKE_CURRENT_BINARY_DIR}/${P_NAME}Config.cmake
                ${CMAKE_CURRENT_BINARY_DIR}/${P_NAME}ConfigVersion.cmake
          DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/${P_NAME})
endfunction()
