// libFuzzer target: the sweep file loader (workflows/sweep_spec.h, SweepSpec::load), then the
// effective sweep it prints.
#include "fuzz_expect.h"
#include "fuzz_scratch.h"
#include "workflows/sweep_spec.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = tissuemesh::fuzz::write_scratch("sweep.yaml", data, size);
  tissuemesh::fuzz::expect_result_or_input_error(
      [&] { (void)tissuemesh::SweepSpec::load(path).to_yaml(); });
  return 0;
}
