// Runs the tissuemesh program as a user would and captures what it prints.
#pragma once

#include "support/test_helpers.h"  // read_file

#include <filesystem>
#include <string>
#include <vector>

namespace tissuemesh::test {

struct CliResult {
  int exit_code = -1;
  std::string out;  ///< stdout
  std::string err;  ///< stderr
};

/// Runs `tissuemesh <args>` (args already shell-quoted where needed) in `workdir`.
CliResult run_cli(const std::string& args, const std::filesystem::path& workdir);

/// Every regular file below `dir` (relative paths), sorted; empty if `dir` does not exist.
std::vector<std::string> files_below(const std::filesystem::path& dir);

}  // namespace tissuemesh::test
