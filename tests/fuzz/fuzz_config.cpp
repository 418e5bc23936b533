// libFuzzer target: the YAML job config loader (app/job_config.h, JobConfig::load: meshing,
// materials, model, export and prone-to-supine sections), then the effective config it prints
// for --print-config.
#include "app/job_config.h"
#include "fuzz_expect.h"
#include "fuzz_scratch.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = tissuemesh::fuzz::write_scratch("config.yaml", data, size);
  tissuemesh::fuzz::expect_result_or_input_error(
      [&] { (void)tissuemesh::app::JobConfig::load(path).to_yaml(); });
  return 0;
}
