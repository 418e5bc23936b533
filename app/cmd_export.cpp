// tissuemesh export MESH -c CONFIG -o DIR [--format febio,abaqus,sofa,vtu,msh]
#include "app/cli_support.h"
#include "app/commands.h"
#include "app/export_outputs.h"
#include "app/job_config.h"
#include "core/errors.h"
#include "core/output_dir.h"
#include "fe_export/registry.h"

#include <iostream>
#include <memory>

namespace tissuemesh::app {

namespace {
struct ExportCliOptions : ModelJobOptions {
  std::vector<std::string> formats;
};

std::string format_help() {
  std::string s = "formats to write (default: the config's export.formats = all):";
  for (const ExportFormat& f : export_formats()) s += "\n  " + f.name + " -> " + f.default_file + ": " + f.description;
  return s;
}
}  // namespace

void add_export_command(CLI::App& cli, Invocation& run) {
  auto opt = std::make_shared<ExportCliOptions>();
  CLI::App* sub = cli.add_subcommand(
      "export", "Mesh + materials + boundary conditions + gravity -> FEBio .feb, Abaqus/CalculiX .inp, SOFA .scn, "
                ".vtu, .msh in DIR, with DIR/export.json");
  add_model_job_options(*sub, *opt);
  sub->add_option("--format", opt->formats, format_help())->delimiter(',');
  sub->callback([opt, &run] {
    run.exit_code = run_guarded("export", [&] {
      const JobConfig config = JobConfig::load(opt->config);
      if (!print_config_or_require_out(opt->print_config, config.to_yaml(), opt->out)) return;
      const std::vector<std::string> formats = opt->formats.empty() ? config.exports.formats : opt->formats;
      for (const std::string& f : formats) export_format_named(f);  // unknown names fail before any work
      OutputDir out(opt->out);
      Progress progress = console_progress();
      const JobModel job = read_job_model(opt->mesh, config, progress);
      export_into(job.model, config, formats, job.inputs, run.command_line, progress, out);
      out.commit();
      std::cout << "wrote " << out.target().string() << "/export.json and the model files listed in it\n";
    });
  });
}

}  // namespace tissuemesh::app
