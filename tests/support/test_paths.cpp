#include "support/test_paths.h"

#include <gtest/gtest.h>

namespace tissuemesh::test {

std::filesystem::path scratch_dir() {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  std::filesystem::path dir = std::filesystem::path(TISSUEMESH_TEST_TMP) /
                              (std::string(info->test_suite_name()) + "." + info->name());
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

std::string config_path(const std::string& name) {
  return std::string(TISSUEMESH_CONFIG_DIR) + "/" + name;
}

}  // namespace tissuemesh::test
