// Why: the check writes the Abaqus deck (fe_export) and runs the built-in solver (solver_check),
// and solver_check must not depend on fe_export (docs/architecture.md, "Modules"), so it lives in
// the program, not in either library.
#include "app/check_outputs.h"

#include "app/cli_support.h"
#include "app/export_outputs.h"
#include "app/solve_outputs.h"
#include "core/errors.h"
#include "core/unit_system.h"
#include "fe_export/registry.h"
#include "solver_check/calculix_dat.h"
#include "solver_check/calculix_run.h"
#include "solver_check/nodal_pressure.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <regex>
#include <set>
#include <sstream>

namespace tissuemesh::app {

namespace fs = std::filesystem;

namespace {

const char* const kFolder = "calculix";
const char* const kJob = "model";
constexpr int kCalculixThreads = 2;
constexpr int kLogTailLines = 20;

/// The last `lines` non-empty lines of `text`.
std::string tail(const std::string& text, int lines) {
  std::vector<std::string> kept;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);)
    if (line.find_first_not_of(" \t\r") != std::string::npos) kept.push_back(line);
  std::string s;
  for (std::size_t i = kept.size() > static_cast<std::size_t>(lines) ? kept.size() - lines : 0; i < kept.size(); ++i)
    s += "  | " + kept[i] + "\n";
  return s;
}

/// "2.20" from ccx's banner ("CalculiX Version 2.20, Copyright(C) ..."); "" when absent.
std::string calculix_version(const std::string& log) {
  std::smatch m;
  static const std::regex kBanner(R"(CalculiX Version ([^\s,]+))");
  return std::regex_search(log, m, kBanner) ? m[1].str() : "";
}

/// Writes the deck of `model` to <staging>/calculix/model.inp (Abaqus writer, no hybrid elements:
/// CalculiX has none). Returns the writer's notes.
std::vector<std::string> write_deck(const Model& model, const JobConfig& job, const std::string& inp_path) {
  ExportOptions options = job.exports;
  std::vector<std::string> notes;
  if (options.abaqus.hybrid) {
    options.abaqus.hybrid = false;
    notes.push_back("export.abaqus.hybrid is true, but CalculiX has no hybrid elements: the check's deck uses "
                    "C3D4/C3D10");
  }
  for (const std::string& n : export_model(model, export_format_named("abaqus"), inp_path, options).notes)
    notes.push_back("abaqus: " + n);
  return notes;
}

/// Runs ccx on the staged deck, stages every file it wrote (their names into `files`, under
/// calculix/) and returns the run; SolverError when it fails.
CalculixRun run_staged(const Model& model, const fs::path& inp, Progress& progress, OutputDir& out,
                       std::vector<std::string>& files) {
  auto stage = progress.stage("run CalculiX");
  stage.note("ccx -i " + std::string(kJob) + ": " + std::to_string(model.nodes.size()) + " nodes, " +
             std::to_string(model.elements.size()) + (model.order == ElementOrder::Linear ? " tet4" : " tet10") +
             " elements, " + std::to_string(kCalculixThreads) +
             " threads (minutes for a full-size breast model: ~2 min for 100K tet4)");
  const CalculixRun run = run_calculix(inp.string(), kCalculixThreads);
  if (run.exit_code != 0)
    throw SolverError("CalculiX (ccx) failed with exit code " + std::to_string(run.exit_code) + " after " +
                      format_double("%.1f", run.seconds) + " s on " + (fs::path(kFolder) / inp.filename()).string() +
                      "; the end of its log:\n" + tail(run.log, kLogTailLines));
  std::set<std::string> names;
  for (const auto& entry : fs::directory_iterator(inp.parent_path()))
    if (entry.is_regular_file() && entry.path() != inp) names.insert(entry.path().filename().string());
  for (const std::string& name : names) {
    files.push_back(std::string(kFolder) + "/" + name);
    out.stage(files.back());
  }
  stage.note("ccx finished in " + format_double("%.1f", run.seconds) + " s, exit code 0");
  return run;
}

/// The last displacements of every node in CalculiX's .dat (ccx node id = model node index + 1).
std::vector<Eigen::Vector3d> calculix_displacements(const CalculixRun& run, const Model& model, Progress& progress) {
  auto stage = progress.stage("read " + std::string(kFolder) + "/" + fs::path(run.dat_path).filename().string());
  const std::vector<DatBlock> blocks = read_calculix_dat(run.dat_path);
  const DatBlock& u = last_block(blocks, "displacements", "NALL");
  // ccx prints the step time with 7 digits: 1.0 exactly at the end of the step.
  if (std::abs(u.time - 1.0) > 1e-6)
    throw SolverError("CalculiX stopped at step time " + std::to_string(u.time) +
                      " before the full load (1.0); see " + std::string(kFolder) + "/" + kJob + ".sta");
  return values_by_node(u, model.nodes.size());
}


std::string table(const CalculixCheck& c, double mm_per_length, const nlohmann::json& equilibrium) {
  const SolutionComparison& d = c.comparison;
  std::ostringstream s;
  char line[200];
  s << "\nCalculiX cross-check of the built-in solver (the same deck: " << kFolder << "/" << kJob << ".inp):\n";
  std::snprintf(line, sizeof line, "  %-30s %12s %12s\n", "", "CalculiX", "built-in");
  s << line;
  std::snprintf(line, sizeof line, "  %-30s %12.4f %12.4f\n", "max |u| [mm]", d.max_u_reference * mm_per_length,
                d.max_u_other * mm_per_length);
  s << line;
  std::snprintf(line, sizeof line, "  %-30s %12.2f %12.2f\n", "wall time [s]", c.calculix_seconds, c.builtin_seconds);
  s << line;
  std::snprintf(line, sizeof line, "  %-30s %12.3g   (%.3g %% of CalculiX's max |u|, node %d)\n",
                "max |u_builtin - u_ccx| [mm]", d.max_diff * mm_per_length, 100.0 * d.max_diff_rel,
                d.max_diff_node + 1);
  s << line;
  std::snprintf(line, sizeof line, "  %-30s %12.3g   (%.3g %% of CalculiX's max |u|)\n",
                "mean |u_builtin - u_ccx| [mm]", d.mean_diff * mm_per_length, 100.0 * d.mean_diff_rel);
  s << line;
  std::snprintf(line, sizeof line, "  %-30s %12.6g   (weight %.6g N, relative imbalance %.1e)\n",
                "built-in reaction [N]", equilibrium["reaction_N"].get<double>(), equilibrium["weight_N"].get<double>(),
                equilibrium["imbalance_rel"].get<double>());
  s << line;
  if (!c.builtin_converged) s << "  the built-in solve did NOT converge: " << c.builtin_message << "\n";
  return s.str();
}

}  // namespace

SolveResult solve_builtin(const Model& model, Progress& progress) {
  auto stage = progress.stage("built-in solve");
  SolveOptions options;
  options.on_step = [&stage](const StepRecord& s) {
    stage.note("load " + format_double("%.4g", s.load_fraction) + ": " + std::to_string(s.iterations) +
               (s.iterations == 1 ? " iteration" : " iterations") +
               (s.accepted ? "" : ", cut back: " + s.note));
  };
  SolveResult r = solve_static(model, options);
  stage.note(r.message);
  return r;
}

std::string require_calculix(const std::string& alternative) {
  const std::string ccx = find_calculix();
  if (!ccx.empty()) return ccx;
  const char* env = std::getenv("TISSUEMESH_CCX");
  const std::string where = env && *env ? "TISSUEMESH_CCX='" + std::string(env) + "' is not an executable"
                                        : "no `ccx` on PATH";
  throw InputError("CalculiX not found (" + where + "). Install it (Debian/Ubuntu: `sudo apt-get install "
                   "calculix-ccx`), set TISSUEMESH_CCX=/path/to/ccx" +
                   (alternative.empty() ? std::string() : ", or " + alternative));
}

Model calculix_comparable_model(const Model& model, std::vector<std::string>& notes) {
  Model comparable = model;
  for (std::size_t t = 0; t < comparable.materials.size(); ++t) {
    MaterialSpec& m = comparable.materials[t];
    if (m.law != MaterialLaw::CompressibleNeoHookean) continue;
    m.law = MaterialLaw::NeoHookean;
    m.C10_Pa = m.mu_Pa / 2.0;
    notes.push_back("tissue '" + model.tissue_names[t] +
                    "': compressible-neo-hookean has no exact CalculiX equivalent; both solvers use the uncoupled "
                    "neo-hookean (Abaqus NEO HOOKE, C10 = mu/2 = " + format_double("%g", m.C10_Pa) + " Pa, same mu " +
                    format_double("%g", m.mu_Pa) + " Pa and K " + format_double("%g", m.K_Pa) + " Pa) for this check");
  }
  if (uses_nodal_pressure(comparable)) {
    comparable.analysis.tet4_pressure = Tet4Pressure::Element;
    notes.push_back("tet4_pressure: nodal is the built-in solver's own element; CalculiX's C3D4 integrates the "
                    "volume term per element, so both solvers use the standard tet4 for this check");
  }
  return comparable;
}

CalculixCheck calculix_check_into(const Model& model, const JobConfig& job, const nlohmann::json& inputs,
                                  const std::string& command_line, Progress& progress, OutputDir& out,
                                  const SolveResult* solved, RunReport* report) {
  const std::string ccx = require_calculix();
  std::vector<std::string> notes;
  const Model comparable = calculix_comparable_model(model, notes);
  const bool unchanged = notes.empty();
  const std::string inp_name = std::string(kFolder) + "/" + kJob + ".inp";
  const fs::path inp = out.stage(inp_name);
  {
    auto stage = progress.stage("write " + inp_name);
    for (const std::string& n : notes) stage.note(n);
    for (const std::string& n : write_deck(comparable, job, inp.string())) {
      stage.note(n);
      notes.push_back(n);
    }
  }
  // The built-in solve before CalculiX: it is the faster of the two and refuses a model it
  // cannot solve (no constraint, ...) up front, before minutes of ccx.
  const bool reuse = solved && unchanged;
  SolveResult own;
  if (!reuse) own = solve_builtin(comparable, progress);
  const SolveResult& builtin = reuse ? *solved : own;
  if (reuse) notes.push_back("built-in: the solve of this run reused (no tissue needed replacing)");

  std::vector<std::string> files{inp_name};
  const CalculixRun run = run_staged(comparable, inp, progress, out, files);
  const std::vector<Eigen::Vector3d> u_ccx = calculix_displacements(run, comparable, progress);

  CalculixCheck c;
  c.builtin_converged = builtin.converged;
  c.builtin_message = builtin.message;
  c.calculix_seconds = run.seconds;
  c.builtin_seconds = builtin.seconds;
  c.comparison = compare_solutions(u_ccx, builtin.displacements);
  if (!builtin.converged)
    notes.push_back("built-in solve did not converge (" + builtin.message + "): the comparison is of its last "
                    "accepted load fraction " + format_double("%g", builtin.load_fraction));

  const double mm = 1.0 / length_from_mm(model.units, 1.0);  // mm per model length unit
  const nlohmann::json summary = model_summary_json(comparable);
  const double newton = 1.0 / force_from_newton(model.units, 1.0);  // N per model force unit
  const double load = builtin.total_load.norm();
  const nlohmann::json equilibrium = {
      {"weight_N", load * newton},
      {"reaction_N", builtin.total_reaction.norm() * newton},
      // |reaction + lambda weight| / |weight|: 0 at equilibrium, also for a solve that stopped early.
      {"imbalance_rel",
       load > 0.0 ? (builtin.total_reaction + builtin.load_fraction * builtin.total_load).norm() / load : 0.0},
      {"solver", "built-in"}};
  const SolutionComparison& d = c.comparison;
  const Eigen::Vector3d at = comparable.nodes[d.max_diff_node];

  nlohmann::json record = run_record_common(progress, command_line);
  record["inputs"] = inputs;
  record["config"] = {{"source", job.source}, {"effective_yaml", job.to_yaml()}};
  record["model"] = summary;
  record["calculix"] = {{"executable", ccx},
                        {"version", calculix_version(run.log)},
                        {"threads", kCalculixThreads},
                        {"seconds", run.seconds},
                        {"exit_code", run.exit_code},
                        {"inp", inp_name},
                        {"dat", std::string(kFolder) + "/" + fs::path(run.dat_path).filename().string()},
                        {"files", files}};
  record["builtin"] = {{"seconds", builtin.seconds},
                       {"converged", builtin.converged},
                       {"message", builtin.message},
                       {"load_fraction", builtin.load_fraction},
                       {"iterations", builtin.total_iterations},
                       {"increments", builtin.steps.size()},
                       {"linear_solver", builtin.linear_solver},
                       {"formulation", builtin.formulation},
                       {"threads", builtin.threads},
                       {"reused_solve", reuse}};
  record["comparison"] = {{"reference", "calculix"},
                          {"max_diff_rel", d.max_diff_rel},
                          {"mean_diff_rel", d.mean_diff_rel},
                          {"max_diff_mm", d.max_diff * mm},
                          {"mean_diff_mm", d.mean_diff * mm},
                          {"max_diff_node", d.max_diff_node + 1},
                          {"max_diff_node_position_mm", {at.x(), at.y(), at.z()}},
                          {"max_u_mm_calculix", d.max_u_reference * mm},
                          {"max_u_mm_builtin", d.max_u_other * mm},
                          {"seconds_calculix", run.seconds},
                          {"seconds_builtin", builtin.seconds}};
  record["equilibrium"] = equilibrium;
  record["notes"] = notes;
  write_text_file(out.stage("check.json"), record.dump(2) + "\n");
  c.record = record;
  std::cout << table(c, mm, equilibrium);
  if (report) {
    std::vector<Eigen::Vector3d> u_mm(builtin.displacements.size());
    for (std::size_t i = 0; i < u_mm.size(); ++i) u_mm[i] = builtin.displacements[i] * mm;
    nlohmann::json solve_record = {{"solver", solver_json(builtin)}};
    report->add_solve(comparable, u_mm, solve_record, "deformed by gravity (built-in solve of the checked model)");
    report->add_table("CalculiX cross-check", table(c, mm, equilibrium));
  }
  return c;
}

}  // namespace tissuemesh::app
