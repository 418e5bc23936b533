// One function per subcommand; each adds itself to the CLI and, when chosen, stores its exit code.
#pragma once

#include <CLI/CLI.hpp>

#include <string>

namespace tissuemesh::app {

struct Invocation {
  std::string command_line;  ///< as typed, for run records
  int exit_code = 0;
};

void add_demo_command(CLI::App& cli, Invocation& run);
void add_phantom_command(CLI::App& cli, Invocation& run);
void add_mesh_command(CLI::App& cli, Invocation& run);
void add_info_command(CLI::App& cli, Invocation& run);
void add_export_command(CLI::App& cli, Invocation& run);
void add_solve_command(CLI::App& cli, Invocation& run);
void add_check_command(CLI::App& cli, Invocation& run);
void add_prone2supine_command(CLI::App& cli, Invocation& run);
void add_sweep_command(CLI::App& cli, Invocation& run);

}  // namespace tissuemesh::app
