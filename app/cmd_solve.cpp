// tissuemesh solve MESH -c CONFIG -o DIR [--threads N]: the model under gravity, solved by the
// built-in nonlinear solver -> DIR/solution.vtu, DIR/solve.json.
#include "app/cli_support.h"
#include "app/commands.h"
#include "app/export_outputs.h"
#include "app/job_config.h"
#include "app/solve_outputs.h"
#include "core/errors.h"
#include "core/output_dir.h"
#include "fe_export/text_format.h"

#include <iostream>
#include <memory>

namespace tissuemesh::app {

namespace {
struct SolveCliOptions : ModelJobOptions {
  int threads = 0;
  bool no_html = false;
};
}  // namespace

void add_solve_command(CLI::App& cli, Invocation& run) {
  auto opt = std::make_shared<SolveCliOptions>();
  CLI::App* sub = cli.add_subcommand(
      "solve",
      "Solve the model of MESH + CONFIG under gravity with the built-in nonlinear solver (neo-Hookean etc., "
      "tet4/tet10, total Lagrangian, Newton with load stepping): DIR/solution.vtu (displacement in mm per node, "
      "Cauchy and von Mises stress in Pa and J per element) and DIR/solve.json (run record: every load increment, "
      "per-tissue mean displacement in mm, reaction and weight in N). Exit 1 when the solve does not converge "
      "(the files of the last accepted load fraction are still written).");
  add_model_job_options(*sub, *opt);
  sub->add_option("--threads", opt->threads, "assembly threads (default 0: $OMP_NUM_THREADS, else all processors)")
      ->check(CLI::NonNegativeNumber);
  add_html_flag(*sub, opt->no_html);
  sub->callback([opt, &run] {
    run.exit_code = run_guarded("solve", [&] {
      const JobConfig config = JobConfig::load(opt->config);
      if (!print_config_or_require_out(opt->print_config, config.to_yaml(), opt->out)) return;
      require_report_assets(!opt->no_html);
      OutputDir out(opt->out);  // fails early on an unwritable folder, before any work
      Progress progress = console_progress();
      RunReport report(!opt->no_html, "tissuemesh solve: " + opt->mesh, run.command_line);
      const JobModel job = read_job_model(opt->mesh, config, progress);
      const nlohmann::json record =
          solve_into(job.model, config, job.inputs, run.command_line, progress, out, nullptr, opt->threads, &report);
      report.stage_into(out);
      out.commit();
      std::cout << "wrote " << out.final_path("solution.vtu").string() << ", " << out.final_path("solve.json").string()
                << (report.enabled() ? ", " + out.final_path("report.html").string() : "") << "\n";
      const nlohmann::json& solver = record["solver"];
      if (!solver["converged"].get<bool>())
        throw SolverError("did not converge: " + solver["message"].get<std::string>() + " (load fraction " +
                          shortest_decimal(solver["load_fraction"].get<double>()) + " reached; see " +
                          out.final_path("solve.json").string() + ")");
    });
  });
}

}  // namespace tissuemesh::app
