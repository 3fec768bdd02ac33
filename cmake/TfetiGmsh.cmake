# Gmsh, for the contact package only: .geo meshing and .msh reading through the C++ API.
# Included by the build tree and by the installed contact config (a static libcontact carries
# Gmsh::Gmsh as a link dependency); find_package(tfeti) and find_package(plasticity) never need it.
include_guard(GLOBAL)
list(APPEND CMAKE_MODULE_PATH "${CMAKE_CURRENT_LIST_DIR}")
find_package(Gmsh 4.8 REQUIRED)
