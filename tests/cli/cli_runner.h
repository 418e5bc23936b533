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

/// configs/phantom-coarse.yaml with `model.element: <element>` (tet4 | tet10), written as
/// <dir>/coarse-<element>.yaml with the material preset path made absolute (usable from any
/// folder). Returns its path.
std::string coarse_config(const std::filesystem::path& dir, const std::string& element);

}  // namespace tissuemesh::test
