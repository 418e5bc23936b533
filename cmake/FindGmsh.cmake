# FindGmsh: the Gmsh SDK (Debian: libgmsh-dev, which ships no CMake config) as Gmsh::Gmsh.
include(${CMAKE_CURRENT_LIST_DIR}/PlainLibrary.cmake)
plain_library(Gmsh Gmsh::Gmsh gmsh.h gmsh)
