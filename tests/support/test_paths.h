// Paths for tests: a fresh scratch folder per test, and the source tree's configs.
#pragma once

#include <filesystem>
#include <string>

namespace tissuemesh::test {

/// A new empty folder under the build tree, named after the running test.
std::filesystem::path scratch_dir();

/// Path of a shipped config, e.g. config_path("phantom.yaml").
std::string config_path(const std::string& name);

}  // namespace tissuemesh::test
