# Compiler instrumentation for the checked builds (docs/reliability.md).
#
# TISSUEMESH_SANITIZE: every target with AddressSanitizer + UndefinedBehaviorSanitizer. Undefined
#   behaviour aborts (-fno-sanitize-recover) so that a finding fails the test that met it instead of
#   scrolling past in its log.
# TISSUEMESH_FUZZ: the same sanitizers plus libFuzzer's coverage instrumentation (clang only);
#   tests/fuzz links its targets with -fsanitize=fuzzer, the libraries get the instrumentation
#   without libFuzzer's main.
set(_tissuemesh_sanitizers -fsanitize=address,undefined -fno-sanitize-recover=undefined
    -fno-omit-frame-pointer)
if(TISSUEMESH_SANITIZE AND TISSUEMESH_FUZZ)
  message(FATAL_ERROR "TISSUEMESH_SANITIZE and TISSUEMESH_FUZZ are separate builds; choose one")
endif()
if(TISSUEMESH_SANITIZE)
  add_compile_options(${_tissuemesh_sanitizers})
  add_link_options(-fsanitize=address,undefined)
endif()
if(TISSUEMESH_FUZZ)
  if(NOT CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
    message(FATAL_ERROR "TISSUEMESH_FUZZ needs clang (libFuzzer): configure with -DCMAKE_CXX_COMPILER=clang++")
  endif()
  add_compile_options(${_tissuemesh_sanitizers} -fsanitize=fuzzer-no-link -g)
  add_link_options(-fsanitize=address,undefined)
endif()
