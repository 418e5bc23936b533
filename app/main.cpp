// tissuemesh: segmented breast MRI -> multi-material finite-element models. See README.md.
#include "app/cli_support.h"
#include "app/commands.h"
#include "app/interrupt_cleanup.h"
#include "core/resources.h"

int main(int argc, char** argv) {
  using namespace tissuemesh::app;
  install_interrupt_cleanup();
  CLI::App cli{"tissuemesh " + tissuemesh::library_versions().at("tissuemesh") +
               ": segmented breast MRI -> conforming multi-material tetrahedral FE models\n"
               "for FEBio, Abaqus/CalculiX and SOFA.\n"
               "Coordinates are LPS millimetres throughout."};
  cli.require_subcommand(1);
  cli.set_version_flag("--version", tissuemesh::library_versions().at("tissuemesh"));
  Invocation run;
  run.command_line = command_line(argc, argv);
  add_demo_command(cli, run);
  add_phantom_command(cli, run);
  add_mesh_command(cli, run);
  add_export_command(cli, run);
  add_solve_command(cli, run);
  add_check_command(cli, run);
  add_prone2supine_command(cli, run);
  add_sweep_command(cli, run);
  add_info_command(cli, run);
  try {
    cli.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // --help / --version exit 0; every usage error is bad input: exit 2.
    const int code = cli.exit(e);
    return code == 0 ? 0 : 2;
  }
  return run.exit_code;
}
