// libFuzzer target: the VTU mesh reader (core/vtu_io.h, read_vtu), the input every command after
// `mesh` starts from.
#include "core/vtu_io.h"
#include "fuzz_expect.h"
#include "fuzz_scratch.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = tissuemesh::fuzz::write_scratch("input.vtu", data, size);
  tissuemesh::fuzz::expect_result_or_input_error([&] { tissuemesh::read_vtu(path); });
  return 0;
}
