// tissuemesh demo [--out DIR]: phantom -> labels on disk -> mesh -> report -> model exports, the main
// job end to end.
#include "app/cli_support.h"
#include "app/commands.h"
#include "app/export_outputs.h"
#include "app/job_config.h"
#include "app/mesh_outputs.h"
#include "core/output_dir.h"
#include "mesher/image_io.h"
#include "mesher/phantom.h"

#include <iostream>
#include <memory>

namespace tissuemesh::app {

namespace {
struct DemoOptions {
  std::string out = "tissuemesh-demo";
  std::string config;
  bool print_config = false;
};
}  // namespace

void add_demo_command(CLI::App& cli, Invocation& run) {
  auto opt = std::make_shared<DemoOptions>();
  CLI::App* sub = cli.add_subcommand(
      "demo", "Built-in phantom -> mesh -> model exports: DIR/phantom.nii.gz, DIR/mesh.vtu, DIR/report.json, "
              "DIR/report.txt, DIR/model.{feb,inp,scn,vtk,vtu,msh}, DIR/export.json");
  sub->add_option("-o,--out", opt->out, "output directory")->capture_default_str();
  sub->add_option("-c,--config", opt->config, "config (default: the built-in phantom config = configs/phantom.yaml)");
  sub->add_flag("--print-config", opt->print_config, "print the effective config and exit");
  sub->callback([opt, &run] {
    run.exit_code = run_guarded("demo", [&] {
      const JobConfig job = opt->config.empty() ? JobConfig::phantom_default() : JobConfig::load(opt->config);
      if (opt->print_config) {
        std::cout << job.to_yaml();
        return;
      }
      const MeshConfig& config = job.require_mesh();
      job.check_materials_cover_tissues();  // before minutes of meshing, not after
      OutputDir out(opt->out);
      Progress progress = console_progress();
      LabelImage generated;
      {
        auto stage = progress.stage("generate phantom");
        generated = make_breast_phantom(config.phantom);
      }
      // Mesh what was written, not what is in memory: the demo then exercises the same reader a
      // user's image goes through.
      const std::string labels_path = out.stage("phantom.nii.gz").string();
      LabelImage labels;
      {
        auto stage = progress.stage("write and re-read phantom.nii.gz");
        write_nifti(generated, labels_path);
        labels = read_label_image(labels_path);
      }
      const nlohmann::json inputs = {{"labels", out.final_path("phantom.nii.gz").string()},
                                     {"labels_generated_by", "built-in phantom"},
                                     {"config", config.source}};
      const TetMesh mesh = mesh_into(labels, "phantom.nii.gz", config, inputs, run.command_line, progress, out);
      const nlohmann::json export_inputs = {{"mesh", out.final_path("mesh.vtu").string()}, {"config", job.source}};
      export_into(mesh, job, job.exports.formats, export_inputs, run.command_line, progress, out);
      out.commit();
      std::cout << "wrote " << out.target().string()
                << "/{phantom.nii.gz, mesh.vtu, report.json, report.txt, model.feb, model.inp, model.scn, "
                   "model.vtk, model.vtu, model.msh, export.json}\n"
                << "open mesh.vtu in ParaView and colour by tissue_id; run `ccx -i model` for CalculiX\n";
    });
  });
}

}  // namespace tissuemesh::app
