#include "core/errors.h"
#include "core/output_dir.h"
#include "support/test_paths.h"

#include <gtest/gtest.h>

#include <fstream>

using namespace tissuemesh;
namespace fs = std::filesystem;

TEST(OutputDir, CommitMovesFilesIntoPlace) {
  const fs::path target = test::scratch_dir() / "out";
  {
    OutputDir out(target);
    std::ofstream(out.stage("a.txt")) << "a";
    EXPECT_FALSE(fs::exists(target / "a.txt"));
    out.commit();
  }
  EXPECT_TRUE(fs::exists(target / "a.txt"));
  EXPECT_EQ(std::distance(fs::directory_iterator(target), fs::directory_iterator()), 1);  // no staging left
}

TEST(OutputDir, FailureLeavesNothingBehind) {
  const fs::path target = test::scratch_dir() / "out";
  try {
    OutputDir out(target);
    std::ofstream(out.stage("a.txt")) << "a";
    throw std::runtime_error("stage failed");
  } catch (const std::runtime_error&) {
  }
  EXPECT_FALSE(fs::exists(target));  // created by the failed run, so removed again
}

TEST(OutputDir, FailureKeepsExistingFolderAsItWas) {
  const fs::path target = test::scratch_dir();
  std::ofstream(target / "keep.txt") << "k";
  try {
    OutputDir out(target);
    std::ofstream(out.stage("new.txt")) << "n";
    throw std::runtime_error("stage failed");
  } catch (const std::runtime_error&) {
  }
  EXPECT_TRUE(fs::exists(target / "keep.txt"));
  EXPECT_FALSE(fs::exists(target / "new.txt"));
  EXPECT_EQ(std::distance(fs::directory_iterator(target), fs::directory_iterator()), 1);
}

TEST(OutputDir, UnwritableTargetIsAnOutputErrorNamingIt) {
  const fs::path file = test::scratch_dir() / "file";
  std::ofstream(file) << "x";
  try {
    OutputDir out(file / "sub");
    FAIL();
  } catch (const OutputError& e) {
    EXPECT_NE(std::string(e.what()).find("file"), std::string::npos);
  }
}
