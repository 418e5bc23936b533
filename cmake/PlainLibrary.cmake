# plain_library(PKG TARGET HEADER LIBRARY): finds a C/C++ library that ships a header and a shared
# library but no CMake config (Debian's libgmsh-dev, libtet1.5-dev), sets PKG_FOUND and defines
# the imported target TARGET. Used by the Find<PKG>.cmake modules beside this file.
include(FindPackageHandleStandardArgs)
macro(plain_library PKG TARGET HEADER LIBRARY)
  string(TOUPPER "${PKG}" _plain_upper)
  find_path(${_plain_upper}_INCLUDE_DIR ${HEADER})
  find_library(${_plain_upper}_LIBRARY NAMES ${LIBRARY})
  find_package_handle_standard_args(${PKG} REQUIRED_VARS ${_plain_upper}_LIBRARY ${_plain_upper}_INCLUDE_DIR)
  if(${PKG}_FOUND AND NOT TARGET ${TARGET})
    add_library(${TARGET} UNKNOWN IMPORTED)
    set_target_properties(${TARGET} PROPERTIES IMPORTED_LOCATION "${${_plain_upper}_LIBRARY}"
                          INTERFACE_INCLUDE_DIRECTORIES "${${_plain_upper}_INCLUDE_DIR}")
  endif()
  mark_as_advanced(${_plain_upper}_INCLUDE_DIR ${_plain_upper}_LIBRARY)
endmacro()
