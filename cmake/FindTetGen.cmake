# FindTetGen: TetGen 1.5 as a library (Debian: libtet1.5-dev, which ships no CMake config) as
# TetGen::TetGen. Users must define TETLIBRARY before including tetgen.h (mesher/tetgen_mesher.cpp).
find_path(TETGEN_INCLUDE_DIR tetgen.h)
find_library(TETGEN_LIBRARY NAMES tet)
include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(TetGen REQUIRED_VARS TETGEN_LIBRARY TETGEN_INCLUDE_DIR)
if(TetGen_FOUND AND NOT TARGET TetGen::TetGen)
  add_library(TetGen::TetGen UNKNOWN IMPORTED)
  set_target_properties(TetGen::TetGen PROPERTIES IMPORTED_LOCATION "${TETGEN_LIBRARY}"
                        INTERFACE_INCLUDE_DIRECTORIES "${TETGEN_INCLUDE_DIR}")
endif()
mark_as_advanced(TETGEN_INCLUDE_DIR TETGEN_LIBRARY)
