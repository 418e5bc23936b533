// tissuemesh check MESH -c CONFIG -o DIR --calculix | --tetgen | --gmsh: cross-checks of a model.
// --calculix solves it with CalculiX and with the built-in solver and compares the displacements
// node by node (DIR/check.json, DIR/calculix/); --tetgen meshes MESH's geometry again with TetGen
// and compares the meshes and their gravity solutions (DIR/check.json, DIR/mesh_tetgen.vtu); --gmsh
// compares our element quality measures with the Gmsh SDK's (DIR/check.json, DIR/quality_gmsh.pos).
#include "app/check_outputs.h"
#include "app/cli_support.h"
#include "app/commands.h"
#include "app/export_outputs.h"
#include "app/gmsh_check.h"
#include "app/job_config.h"
#include "app/tetgen_check.h"
#include "core/errors.h"
#include "core/output_dir.h"

#include <iostream>
#include <memory>

namespace tissuemesh::app {

namespace {
struct CheckCliOptions : ModelJobOptions {
  bool calculix = false;
  bool tetgen = false;
  bool gmsh = false;
  std::string target = "tumor";
  bool no_html = false;
};
}  // namespace

void add_check_command(CLI::App& cli, Invocation& run) {
  auto opt = std::make_shared<CheckCliOptions>();
  CLI::App* sub = cli.add_subcommand(
      "check", "Cross-checks of the model of MESH + CONFIG: --calculix solves it with CalculiX (ccx) and with the "
               "built-in solver and compares the displacements (DIR/check.json, DIR/calculix/); --tetgen meshes "
               "MESH's tissue boundaries again with TetGen and compares meshes and gravity solutions "
               "(DIR/check.json, DIR/mesh_tetgen.vtu); --gmsh compares our element quality figures with the Gmsh "
               "SDK's (DIR/check.json, DIR/quality_gmsh.pos)");
  add_model_job_options(*sub, *opt);
  sub->add_flag("--calculix", opt->calculix,
                "CalculiX (ccx, 2 threads) against the built-in solver on the same deck: max and mean nodal "
                "difference relative to the max displacement; compressible-neo-hookean tissues are checked as "
                "the uncoupled neo-hookean (noted)");
  sub->add_flag("--tetgen", opt->tetgen,
                "TetGen 1.5 on MESH's boundary and interface triangles (config `tetgen:`): per-tissue volumes, "
                "counts, dihedral angles, interface areas, the radius-edge ratio against tetgen.radius_edge_ratio "
                "and against the bound the input triangles force, and the --target tissue's mean displacement "
                "under gravity on both meshes (built-in solver)");
  sub->add_flag("--gmsh", opt->gmsh,
                "the Gmsh SDK's gamma and SICN of every tet of MESH against our radius ratio and SICN: per-tissue "
                "minima and means by both, largest per-tet difference; exit 1 when they disagree");
  sub->add_option("--target", opt->target, "tissue whose displacement --tetgen compares (default tumor)");
  add_html_flag(*sub, opt->no_html);
  sub->callback([opt, &run] {
    run.exit_code = run_guarded("check", [&] {
      const JobConfig config = JobConfig::load(opt->config);
      if (!print_config_or_require_out(opt->print_config, config.to_yaml(), opt->out)) return;
      if (int(opt->calculix) + int(opt->tetgen) + int(opt->gmsh) != 1)
        throw InputError("choose one cross-check: --calculix, --tetgen or --gmsh");
      require_report_assets(!opt->no_html);
      RunReport report(!opt->no_html, "tissuemesh check: " + opt->mesh, run.command_line);
      if (opt->gmsh) {
        OutputDir out(opt->out);
        Progress progress = console_progress();
        const TetMesh mesh = read_job_mesh(opt->mesh, progress);
        const GmshCheck check =
            gmsh_check_into(mesh, job_inputs(opt->mesh, config),
                            {{"source", config.source}, {"effective_yaml", config.to_yaml()}}, run.command_line,
                            progress, out);
        report.add_mesh_view(mesh);
        report.add_record_table("Gmsh quality check (check.json)", check.record);
        report.stage_into(out);
        out.commit();
        std::cout << "wrote " << out.target().string() << "/check.json and " << out.target().string()
                  << "/quality_gmsh.pos\n";
        if (!check.agree) throw Error("Gmsh's element quality disagrees with ours (see check.json)");
        return;
      }
      if (opt->tetgen) {
        OutputDir out(opt->out);
        Progress progress = console_progress();
        const TetMesh mesh = read_job_mesh(opt->mesh, progress);
        const TetgenCheck check = tetgen_check_into(mesh, opt->target, config, job_inputs(opt->mesh, config),
                                                    run.command_line, progress, out);
        report.add_mesh_view(mesh);
        report.add_record_table("TetGen cross-check (check.json)", check.record);
        report.stage_into(out);
        out.commit();
        std::cout << "wrote " << out.target().string() << "/check.json and " << out.target().string()
                  << "/mesh_tetgen.vtu\n";
        if (!check.both_converged)
          throw SolverError("a built-in solve did not converge (outputs written; see check.json)");
        return;
      }
      require_calculix();  // before reading and building
      OutputDir out(opt->out);
      Progress progress = console_progress();
      const JobModel job = read_job_model(opt->mesh, config, progress);
      const CalculixCheck check =
          calculix_check_into(job.model, config, job.inputs, run.command_line, progress, out, nullptr, &report);
      report.note_timings(check.record);
      report.stage_into(out);
      out.commit();
      std::cout << "wrote " << out.target().string() << "/check.json and " << out.target().string()
                << "/calculix/ (the deck CalculiX solved and its results)\n";
      if (!check.builtin_converged)
        throw SolverError("the built-in solve did not converge: " + check.builtin_message +
                          " (outputs written; the comparison is of its last accepted increment)");
    });
  });
}

}  // namespace tissuemesh::app
