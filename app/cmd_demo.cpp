// tissuemesh demo [--out DIR]: phantom -> labels on disk -> mesh -> report -> model exports ->
// built-in solve -> CalculiX cross-check, the main job end to end; with --prone2supine also the
// prone-to-supine workflow on the mesh.
#include "app/check_outputs.h"
#include "app/cli_support.h"
#include "app/commands.h"
#include "app/export_outputs.h"
#include "app/job_config.h"
#include "app/mesh_outputs.h"
#include "app/prone2supine_outputs.h"
#include "app/solve_outputs.h"
#include "core/errors.h"
#include "core/output_dir.h"
#include "image/image_io.h"
#include "image/make_phantom.h"

#include <cstdio>
#include <iostream>
#include <memory>
#include <optional>

namespace tissuemesh::app {

namespace {
struct DemoOptions {
  std::string out = "tissuemesh-demo";
  std::string config;
  bool print_config = false;
  bool skip_calculix = false;
  bool prone2supine = false;
  bool no_html = false;
};

/// The figures of the run, last on the console: what the solve found (its record, solve.json) and
/// how it compares with CalculiX.
void print_figures(const nlohmann::json& solve_record, const CalculixCheck* check) {
  const nlohmann::json& res = solve_record["results"];
  char line[256];
  const bool converged = solve_record["solver"]["converged"].get<bool>();
  std::cout << "\nresults (built-in solver" << (converged ? "" : ", NOT converged") << "):\n";
  std::snprintf(line, sizeof line, "  %-30s %.3f mm (node %d)\n", "max displacement",
                res["max_displacement_mm"].get<double>(), res["max_displacement_node"].get<int>());
  std::cout << line;
  for (const auto& t : res["tissues"])
    if (t["name"] == "tumor") {
      const auto& u = t["centroid_displacement_mm"];
      std::snprintf(line, sizeof line, "  %-30s %.3f mm = (%.3f, %.3f, %.3f) mm LPS\n", "tumour centroid displacement",
                    t["centroid_displacement_magnitude_mm"].get<double>(), u[0].get<double>(), u[1].get<double>(),
                    u[2].get<double>());
      std::cout << line;
    }
  const auto norm = [](const nlohmann::json& v) {
    return Eigen::Vector3d(v[0].get<double>(), v[1].get<double>(), v[2].get<double>()).norm();
  };
  std::snprintf(line, sizeof line, "  %-30s %.5f N vs %.5f N (relative imbalance %.1e)\n", "reaction vs weight",
                norm(res["total_reaction_N"]), norm(res["total_weight_N"]),
                res["reaction_vs_weight_rel"].is_null() ? 0.0 : res["reaction_vs_weight_rel"].get<double>());
  std::cout << line;
  const double builtin_s = solve_record["solver"]["seconds"].get<double>();
  if (check) {
    std::snprintf(line, sizeof line, "  %-30s max %.3g %%, mean %.3g %% of the max displacement\n",
                  "difference vs CalculiX", 100.0 * check->comparison.max_diff_rel,
                  100.0 * check->comparison.mean_diff_rel);
    std::cout << line;
    std::snprintf(line, sizeof line, "  %-30s built-in %.1f s, CalculiX %.1f s\n", "solve time", builtin_s,
                  check->calculix_seconds);
  } else {
    std::snprintf(line, sizeof line, "  %-30s built-in %.1f s (no CalculiX cross-check)\n", "solve time", builtin_s);
  }
  std::cout << line;
}
}  // namespace

void add_demo_command(CLI::App& cli, Invocation& run) {
  auto opt = std::make_shared<DemoOptions>();
  CLI::App* sub = cli.add_subcommand(
      "demo", "Built-in phantom -> mesh -> model exports -> built-in solve -> CalculiX cross-check: "
              "DIR/phantom.nii.gz, DIR/mesh.vtu, DIR/report.json, DIR/report.txt, DIR/model.{feb,inp,scn,vtk,vtu,msh}, "
              "DIR/export.json, DIR/solution.vtu, DIR/solve.json, DIR/check.json, DIR/calculix/");
  sub->add_option("-o,--out", opt->out, "output directory")->capture_default_str();
  sub->add_option("-c,--config", opt->config, "config (default: the built-in phantom config = configs/phantom.yaml)");
  sub->add_flag("--print-config", opt->print_config, "print the effective config and exit");
  sub->add_flag("--skip-calculix", opt->skip_calculix,
                "do not run the CalculiX cross-check (no check.json, no calculix/); the built-in solve still runs");
  sub->add_flag("--prone2supine", opt->prone2supine,
                "also run prone-to-supine on the mesh (the phantom is the prone shape): DIR/reference.vtu, supine.vtu, "
                "prone_check.vtu, supine_model.*, prone2supine.json, and points.csv for the tumour centre");
  add_html_flag(*sub, opt->no_html);
  sub->callback([opt, &run] {
    run.exit_code = run_guarded("demo", [&] {
      const JobConfig job = opt->config.empty() ? JobConfig::phantom_default() : JobConfig::load(opt->config);
      if (opt->print_config) {
        std::cout << job.to_yaml();
        return;
      }
      const MeshConfig& config = job.require_mesh();
      job.check_materials_cover_tissues();  // before minutes of meshing, not after
      if (!opt->skip_calculix) require_calculix("run the demo with --skip-calculix");
      require_report_assets(!opt->no_html);
      OutputDir out(opt->out);
      Progress progress = console_progress();
      RunReport report(!opt->no_html, "tissuemesh demo: the built-in phantom, meshed and solved", run.command_line);
      LabelImage generated;
      {
        auto stage = progress.stage("generate phantom");
        generated = make_phantom(config.phantom);
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
      const TetMesh mesh = mesh_into(labels, "phantom.nii.gz", config, inputs, run.command_line, progress, out, &report);
      const nlohmann::json export_inputs = {{"mesh", out.final_path("mesh.vtu").string()}, {"config", job.source}};
      const Model model = build_job_model(mesh, job, progress);
      export_into(model, job, job.exports.formats, export_inputs, run.command_line, progress, out);
      SolveResult solved;
      const nlohmann::json solve_record =
          solve_into(model, job, export_inputs, run.command_line, progress, out, &solved, 0, &report);
      std::optional<CalculixCheck> check;
      if (opt->skip_calculix)
        std::cout << "\nCalculiX cross-check skipped (--skip-calculix)\n";
      else if (!solved.converged)
        std::cout << "\nCalculiX cross-check not run: the built-in solve did not converge\n";
      else
        check = calculix_check_into(model, job, export_inputs, run.command_line, progress, out, &solved, &report);
      std::optional<Prone2SupineOutcome> p2s;
      if (opt->prone2supine) {
        // The phantom's tumour centre as a landmark (the breast phantom only: other kinds have none).
        Prone2SupineRequest request;
        if (config.phantom.kind == "breast") {
          request.points_path = out.stage("landmarks.csv").string();
          const Eigen::Vector3d& c = config.phantom.tumor_center_mm;
          write_text_file(request.points_path, "name,x_mm,y_mm,z_mm\ntumour_centre," + format_double("%.17g", c.x()) +
                                                   "," + format_double("%.17g", c.y()) + "," +
                                                   format_double("%.17g", c.z()) + "\n");
        }
        nlohmann::json p2s_inputs = export_inputs;
        if (!request.points_path.empty()) p2s_inputs["points"] = out.final_path("landmarks.csv").string();
        p2s = prone2supine_into(mesh, job, request, p2s_inputs, run.command_line, progress, out, &report);
      }
      report.stage_into(out);
      out.commit();
      print_figures(solve_record, check ? &*check : nullptr);
      std::cout << "\nwrote " << out.target().string()
                << "/{phantom.nii.gz, mesh.vtu, report.json, report.txt, model.feb, model.inp, model.scn, "
                   "model.vtk, model.vtu, model.msh, export.json, solution.vtu, solve.json"
                << (report.enabled() ? ", report.html" : "")
                << (check ? ", check.json, calculix/" : "") << "}\n"
                << (report.enabled() ? "open report.html in a browser (3D view, plots, tables), or " : "")
                << "open solution.vtu in ParaView, colour by tissue_id and warp by displacement"
                << (check ? "; calculix/ holds the deck CalculiX solved and its results\n" : "\n");
      if (p2s)
        std::cout << "prone to supine: " << out.target().string()
                  << "/{reference.vtu, supine.vtu, prone_check.vtu, supine_model.{feb,inp,scn,vtk}, prone2supine.json"
                  << (config.phantom.kind == "breast" ? ", landmarks.csv, points.csv" : "")
                  << "}; open supine.vtu and warp by displacement_from_prone (mm) to see the supine shape\n";
      if (!solved.converged)
        throw SolverError("the built-in solve did not converge: " + solved.message + " (outputs written)");
      if (p2s && !p2s->converged)
        throw SolverError("prone to supine did not converge: " + p2s->failure + " (outputs written)");
      if (check && !check->builtin_converged)
        throw SolverError("the built-in solve of the CalculiX check did not converge: " + check->builtin_message +
                          " (outputs written)");
    });
  });
}

}  // namespace tissuemesh::app
