#include "core/errors.h"
#include "core/output_dir.h"
#include "support/test_helpers.h"
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

TEST(OutputDir, NamesWithFoldersAreStagedAndCommitted) {
  const fs::path target = test::scratch_dir() / "out";
  for (const char* text : {"first", "second"}) {  // the second run replaces files in an existing sub-folder
    OutputDir out(target);
    std::ofstream(out.stage("sub/deeper/a.txt")) << text;
    std::ofstream(out.stage("sub/b.txt")) << text;
    EXPECT_EQ(fs::exists(target / "sub"), std::string(text) == "second") << "only the commit creates it";
    out.commit();
  }
  EXPECT_EQ(test::read_file(target / "sub/deeper/a.txt"), "second");
  EXPECT_EQ(test::read_file(target / "sub/b.txt"), "second");
  EXPECT_EQ(std::distance(fs::directory_iterator(target), fs::directory_iterator()), 1);  // only sub/
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

TEST(OutputDir, FailedCommitRestoresWhatWasThere) {
  const fs::path target = test::scratch_dir();
  std::ofstream(target / "a.txt") << "old";
  fs::create_directories(target / "b.txt" / "blocker");  // a non-empty folder cannot be replaced by a file
  std::ofstream(target / "b.txt" / "blocker" / "x") << "x";
  {
    OutputDir out(target);
    std::ofstream(out.stage("a.txt")) << "new";
    std::ofstream(out.stage("b.txt")) << "new";
    EXPECT_THROW(out.commit(), OutputError);
  }
  EXPECT_EQ(test::read_file(target / "a.txt"), "old");  // put back
  EXPECT_TRUE(fs::is_directory(target / "b.txt"));
}

TEST(OutputDir, StagedButUnwrittenFileIsAnError) {
  OutputDir out(test::scratch_dir() / "out");
  out.stage("never.txt");
  EXPECT_THROW(out.commit(), OutputError);
}
