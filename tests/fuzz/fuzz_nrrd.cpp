// libFuzzer target: the NRRD reader (image/image_header.h, image/image_io.h). An input holding
// the line "@@detached@@" is a detached pair: the text before it is written as input.nhdr, the
// bytes after it as both data.raw and data.gz (the seeds' headers name one of them in
// `data file`); any other input is an attached .nrrd (raw or gzip, as its header says).
#include "fuzz_expect.h"
#include "fuzz_scratch.h"
#include "image/image_io.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace tissuemesh::fuzz;
  const std::string path =
      write_image_input(data, size, "input.nrrd", "input.nhdr", {"data.raw", "data.gz"});
  expect_result_or_input_error([&] { tissuemesh::read_label_image(path); });
  return 0;
}
