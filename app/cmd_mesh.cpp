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
};
}  // namespace

void add_mesh_command(CLI::App& cli, Invocation& run) {
  auto opt = std::make_shared<MeshOptions>();
  CLI::App* sub = cli.add_subcommand("mesh", "Mesh a label image: DIR/mesh.vtu (pipeline: surface: DIR/surface.vtp, DIR/junctions.vtp), DIR/report.json, DIR/report.txt");
  sub->add_option("LABELS", opt->labels, "label image (.nii, .nii.gz, .nrrd, .nhdr, .mha, .mhd)")->required();
  sub->add_option("-c,--config", opt->config, "meshing config (YAML), e.g. configs/breast-generic.yaml")->required();
  sub->add_option("-o,--out", opt->out, "output directory");
  sub->add_flag("--print-config", opt->print_config, "print the effective config (defaults filled in) and exit");
  sub->callback([opt, &run] {
    run.exit_code = run_guarded("mesh", [&] {
      const JobConfig job = JobConfig::load(opt->config);
      const MeshConfig& config = job.require_mesh();
      if (!print_config_or_require_out(opt->print_config, job.to_yaml(), opt->out)) return;
      OutputDir out(opt->out);  // fails early on an unwritable folder, before any work
      Progress progress = console_progress();
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
        surface_into(labels, opt->labels, config, inputs, run.command_line, progress, out);
        out.commit();
        std::cout << "wrote " << out.final_path("surface.vtp").string()
                  << ", junctions.vtp, mesh.vtu, report.json, report.txt\n";
        return;
      }
      mesh_into(labels, opt->labels, config, inputs, run.command_line, progress, out);
      out.commit();
      std::cout << "wrote " << out.final_path("mesh.vtu").string() << ", report.json, report.txt\n";
    });
  });
}

}  // namespace tissuemesh::app
