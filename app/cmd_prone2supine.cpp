// tissuemesh prone2supine MESH -c CONFIG -o DIR [--points P.csv] [--image LABELS]: the unloaded
// reference of a mesh imaged prone and its supine shape (app/prone2supine_outputs.h).
#include "app/cli_support.h"
#include "app/commands.h"
#include "app/export_outputs.h"
#include "app/job_config.h"
#include "app/prone2supine_outputs.h"
#include "core/errors.h"
#include "core/output_dir.h"

#include <iostream>
#include <memory>

namespace tissuemesh::app {

namespace {
struct Prone2SupineCliOptions : ModelJobOptions {
  Prone2SupineRequest request;
  bool no_html = false;
};
}  // namespace

void add_prone2supine_command(CLI::App& cli, Invocation& run) {
  auto opt = std::make_shared<Prone2SupineCliOptions>();
  CLI::App* sub = cli.add_subcommand(
      "prone2supine",
      "From a mesh of the prone (imaged) breast: the unloaded reference by the fixed-point iteration, then the "
      "supine shape under supine gravity (config section prone2supine:). DIR/reference.vtu (a mesh), "
      "DIR/supine.vtu, DIR/prone_check.vtu, DIR/supine_model.{feb,inp,scn,vtk}, DIR/prone2supine.json; "
      "DIR/points.csv with --points, DIR/supine_labels.nii.gz with --image. Exit 1 when the iteration or the supine "
      "solve does not converge (the files of the best iterate are still written).");
  add_model_job_options(*sub, *opt);
  sub->add_option("--points", opt->request.points_path,
                  "landmarks CSV 'name,x,y,z' (prone LPS mm) -> DIR/points.csv with reference and supine positions");
  sub->add_option("--image", opt->request.image_path,
                  "the prone label image -> DIR/supine_labels.nii.gz, its labels carried into the supine shape");
  sub->add_option("--threads", opt->request.threads,
                  "assembly threads (default 0: $OMP_NUM_THREADS, else all processors)")
      ->check(CLI::NonNegativeNumber);
  add_html_flag(*sub, opt->no_html);
  sub->callback([opt, &run] {
    run.exit_code = run_guarded("prone2supine", [&] {
      const JobConfig config = JobConfig::load(opt->config);
      if (!print_config_or_require_out(opt->print_config, config.to_yaml(), opt->out)) return;
      require_report_assets(!opt->no_html);
      OutputDir out(opt->out);  // fails early on an unwritable folder, before any work
      Progress progress = console_progress();
      RunReport report(!opt->no_html, "tissuemesh prone2supine: " + opt->mesh, run.command_line);
      const TetMesh mesh = read_job_mesh(opt->mesh, progress);
      nlohmann::json inputs = job_inputs(opt->mesh, config);
      if (!opt->request.points_path.empty()) inputs["points"] = std::filesystem::absolute(opt->request.points_path);
      if (!opt->request.image_path.empty()) inputs["image"] = std::filesystem::absolute(opt->request.image_path);
      const Prone2SupineOutcome outcome =
          prone2supine_into(mesh, config, opt->request, inputs, run.command_line, progress, out, &report);
      report.stage_into(out);
      out.commit();
      std::cout << "wrote " << out.target().string()
                << "/{reference.vtu, supine.vtu, prone_check.vtu, supine_model.{feb,inp,scn,vtk}, prone2supine.json"
                << (opt->request.points_path.empty() ? "" : ", points.csv")
                << (opt->request.image_path.empty() ? "" : ", supine_labels.nii.gz")
                << (report.enabled() ? ", report.html" : "") << "}\n";
      if (!outcome.converged)
        throw SolverError("did not converge: " + outcome.failure + " (the best iterate is written; see " +
                          out.final_path("prone2supine.json").string() + ")");
    });
  });
}

}  // namespace tissuemesh::app
