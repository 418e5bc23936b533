#include "cli/cli_runner.h"

#include "support/test_paths.h"

#include <sys/wait.h>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <regex>
#include <vector>

namespace tissuemesh::test {

CliResult run_cli(const std::string& args, const std::filesystem::path& workdir) {
  const auto out = workdir / ".cli_stdout", err = workdir / ".cli_stderr";
  const std::string cmd = "cd '" + workdir.string() + "' && '" + TISSUEMESH_EXE + "' " + args + " > '" +
                          out.string() + "' 2> '" + err.string() + "'";
  const int status = std::system(cmd.c_str());
  CliResult r;
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.out = read_file(out);
  r.err = read_file(err);
  std::filesystem::remove(out);
  std::filesystem::remove(err);
  return r;
}

std::vector<std::string> files_below(const std::filesystem::path& dir) {
  std::vector<std::string> files;
  if (!std::filesystem::exists(dir)) return files;
  for (const auto& e : std::filesystem::recursive_directory_iterator(dir))
    if (e.is_regular_file()) files.push_back(std::filesystem::relative(e.path(), dir).string());
  std::sort(files.begin(), files.end());
  return files;
}

std::string coarse_config(const std::filesystem::path& dir, const std::string& element) {
  std::string text = read_file(config_path("phantom-coarse.yaml"));
  text = std::regex_replace(text, std::regex("element: tet4"), "element: " + element);
  text = std::regex_replace(text, std::regex("preset: materials/"),
                            "preset: " + std::string(TISSUEMESH_CONFIG_DIR) + "/materials/");
  const auto path = dir / ("coarse-" + element + ".yaml");
  std::ofstream(path) << text;
  return path.string();
}

}  // namespace tissuemesh::test
