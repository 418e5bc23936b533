// libFuzzer target: the NIfTI reader (image/image_io.h, read_label_image). An input that starts
// with the gzip magic is read as .nii.gz, any other as .nii.
#include "fuzz_expect.h"
#include "fuzz_scratch.h"
#include "image/image_io.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const bool gz = size >= 2 && data[0] == 0x1f && data[1] == 0x8b;
  const std::string path =
      tissuemesh::fuzz::write_scratch(gz ? "input.nii.gz" : "input.nii", data, size);
  tissuemesh::fuzz::expect_result_or_input_error([&] { tissuemesh::read_label_image(path); });
  return 0;
}
