# tissuemesh_add_module(NAME <target> SOURCES ... HEADERS ... DEPS ...)
# One library per module folder. Headers are included as "<folder>/<file>.h" both in the
# build tree (project root on the include path) and after install (include/tissuemesh).
function(tissuemesh_add_module)
  cmake_parse_arguments(M "" "NAME;FOLDER" "SOURCES;HEADERS;PUBLIC_DEPS;PRIVATE_DEPS" ${ARGN})
  add_library(tissuemesh_${M_NAME} ${M_SOURCES})
  add_library(tissuemesh::${M_NAME} ALIAS tissuemesh_${M_NAME})
  set_target_properties(tissuemesh_${M_NAME} PROPERTIES EXPORT_NAME ${M_NAME}
                        OUTPUT_NAME tissuemesh_${M_NAME})
  target_include_directories(tissuemesh_${M_NAME} PUBLIC
    $<BUILD_INTERFACE:${PROJECT_SOURCE_DIR}>
    $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}/tissuemesh>)
  target_link_libraries(tissuemesh_${M_NAME} PUBLIC ${M_PUBLIC_DEPS} PRIVATE ${M_PRIVATE_DEPS})
  install(TARGETS tissuemesh_${M_NAME} EXPORT tissuemeshTargets
          ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
          LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR})
  install(FILES ${M_HEADERS} DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/tissuemesh/${M_FOLDER})
endfunction()
