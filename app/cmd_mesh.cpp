// tissuemesh mesh LABELS -c CONFIG -o DIR
#include "app/cli_support.h"
#include "app/commands.h"
#include "app/job_config.h"
#include "app/mesh_outputs.h"
#include "core/errors.h"
#include "core/output_dir.h"
#include "image/image_io.h"
#include "pipeline/mesh_memory.h"

#include <filesystem>
#include <iostream>
#include <memory>

namespace tissuemesh::app {

namespace {
struct MeshOptions {
  std::string labels, config, out;
  bool print_config = false;
  bool no_html = false;
};
}  // namespace

void add_mesh_command(CLI::App& cli, Invocation& run) {
  auto opt = std::make_shared<MeshOptions>();
  CLI::App* sub = cli.add_subcommand("mesh", "Mesh a label image: DIR/mesh.vtu (pipeline: surface: DIR/surface.vtp, DIR/junctions.vtp), DIR/report.json, DIR/report.txt, DIR/report.html");
  sub->add_option("LABELS", opt->labels, "label image (.nii, .nii.gz, .nrrd, .nhdr, .mha, .mhd)")->required();
  sub->add_option("-c,--config", opt->config, "meshing config (YAML), e.g. configs/breast-generic.yaml")->required();
  sub->add_option("-o,--out", opt->out, "output directory");
  sub->add_flag("--print-config", opt->print_config, "print the effective config (defaults filled in) and exit");
  add_html_flag(*sub, opt->no_html);
  sub->callback([opt, &run] {
    run.exit_code = run_guarded("mesh", [&] {
      const JobConfig job = JobConfig::load(opt->config);
      const MeshConfig& config = job.require_mesh();
      if (!print_config_or_require_out(opt->print_config, job.to_yaml(), opt->out)) return;
      require_report_assets(!opt->no_html);
      OutputDir out(opt->out);  // fails early on an unwritable folder, before any work
      Progress progress = console_progress();
      RunReport report(!opt->no_html, "tissuemesh mesh: " + opt->labels, run.command_line);
      LabelImage labels;
      {
        auto stage = progress.stage("read " + opt->labels);
        labels = read_label_image(opt->labels);
      }
      require_mesh_memory(labels, config, opt->labels);
      const nlohmann::json inputs = {{"labels", std::filesystem::absolute(opt->labels).string()},
                                     {"labels_bytes", std::filesystem::file_size(opt->labels)},
                                     {"config", std::filesystem::absolute(opt->config).string()}};
      if (config.pipeline == "surface") {
        surface_into(labels, opt->labels, config, inputs, run.command_line, progress, out, &report);
        report.stage_into(out);
        out.commit();
        std::cout << "wrote " << out.final_path("surface.vtp").string() << ", junctions.vtp, mesh.vtu, report.json, "
                  << "report.txt" << (report.enabled() ? ", report.html" : "") << "\n";
        return;
      }
      mesh_into(labels, opt->labels, config, inputs, run.command_line, progress, out, &report);
      report.stage_into(out);
      out.commit();
      std::cout << "wrote " << out.final_path("mesh.vtu").string() << ", report.json, report.txt"
                << (report.enabled() ? ", report.html" : "") << "\n";
    });
  });
}

}  // namespace tissuemesh::app
