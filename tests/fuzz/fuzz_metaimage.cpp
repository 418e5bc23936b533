// libFuzzer target: the MetaImage reader (image/image_header.h, image/image_io.h). An input
// holding the line "@@detached@@" is a detached pair: the text before it is written as
// input.mhd, the bytes after it as data.raw (which the seeds' ElementDataFile names); any other
// input is an attached .mha (ElementDataFile = LOCAL).
#include "fuzz_expect.h"
#include "fuzz_scratch.h"
#include "image/image_io.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace tissuemesh::fuzz;
  const std::string path = write_image_input(data, size, "input.mha", "input.mhd", {"data.raw"});
  expect_result_or_input_error([&] { tissuemesh::read_label_image(path); });
  return 0;
}
