# FindTetGen: TetGen 1.5 as a library (Debian: libtet1.5-dev, which ships no CMake config) as
# TetGen::TetGen. Users must define TETLIBRARY before including tetgen.h (volume/tetgen_mesher.cpp).
include(${CMAKE_CURRENT_LIST_DIR}/PlainLibrary.cmake)
plain_library(TetGen TetGen::TetGen tetgen.h tet)
