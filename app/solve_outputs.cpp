#include "app/solve_outputs.h"

#include "app/cli_support.h"
#include "app/export_outputs.h"
#include "core/unit_system.h"
#include "fe_export/vtu/write_model_vtu.h"
#include "solver_check/cell_fields.h"
#include "solver_check/tissue_motion.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <limits>
#include <stdexcept>

namespace tissuemesh::app {

namespace {

const char* const kStressComponents[6] = {"xx", "yy", "zz", "xy", "yz", "xz"};

std::string vec_text(const Eigen::Vector3d& v, const char* fmt) {
  return "(" + format_double(fmt, v.x()) + ", " + format_double(fmt, v.y()) + ", " + format_double(fmt, v.z()) + ")";
}

}  // namespace

std::string step_line(const StepRecord& s, int attempt) {
  std::string line = "increment " + std::to_string(attempt) + ": load " + format_double("%.4g", s.load_fraction) +
                     " (+" + format_double("%.4g", s.increment) + "), " + std::to_string(s.iterations) +
                     (s.iterations == 1 ? " iteration" : " iterations");
  if (!s.residual_norms.empty()) line += ", residual " + format_double("%.2e", s.residual_norms.back());
  line += s.accepted ? ", accepted" : ", cut back (" + s.note + ")";
  if (s.accepted && !s.note.empty()) line += " (" + s.note + ")";
  return line + ", " + format_double("%.2f", s.seconds) + " s";
}

namespace {

nlohmann::json step_json(const StepRecord& s) {
  return {{"load_fraction", s.load_fraction}, {"increment", s.increment},       {"iterations", s.iterations},
          {"residual_norms", s.residual_norms}, {"step_lengths", s.step_lengths}, {"accepted", s.accepted},
          {"note", s.note},                   {"seconds", s.seconds}};
}

}  // namespace

// A NaN or infinity must never reach a file (nlohmann would write it as null): throws naming the
// place. SolveResult is NaN-free by contract, so this is a programmer error (exit 1).
void require_finite(const nlohmann::json& j, const std::string& where) {
  if (j.is_number_float() && !std::isfinite(j.get<double>()))
    throw std::logic_error("internal error: non-finite value in solve.json at " + where + "; nothing written");
  if (j.is_object())
    for (const auto& [key, value] : j.items()) require_finite(value, where + "." + key);
  if (j.is_array())
    for (std::size_t i = 0; i < j.size(); ++i) require_finite(j[i], where + "[" + std::to_string(i) + "]");
}

namespace {

SolveResult run_solver(const Model& model, int threads, Progress& progress) {
  auto stage = progress.stage(std::string("solve (built-in, ") + formulation_name(model) + ", " +
                              std::to_string(3 * model.nodes.size()) + " dofs)");
  SolveOptions options;
  options.threads = threads;
  int attempt = 0;
  options.on_step = [&](const StepRecord& s) { stage.note(step_line(s, ++attempt), s.accepted ? s.load_fraction : s.load_fraction - s.increment); };
  SolveResult r = solve_static(model, options);
  stage.note(std::to_string(r.free_dofs) + " free dofs, " + r.linear_solver + " (" +
             std::to_string(r.factorisations) + " factorisations, " + std::to_string(r.linear_iterations) +
             " CG iterations preconditioned by " + r.cg_preconditioner + "), " + std::to_string(r.threads) +
             (r.threads == 1 ? " thread: " : " threads: ") + r.message);
  return r;
}

// What solution.vtu adds to the model VTU (header comment of solve_outputs.h).
ModelVtuData solution_arrays(const SolveResult& r, const CellFields& fields, double mm_per_length) {
  ModelVtuData d;
  VtuArray u{"displacement", 3, {"x", "y", "z"}, {}};
  for (const Eigen::Vector3d& v : r.displacements)
    for (int k = 0; k < 3; ++k) u.values.push_back(v[k] * mm_per_length);
  d.point_data.push_back(std::move(u));
  VtuArray sigma{"cauchy_stress", 6, {std::begin(kStressComponents), std::end(kStressComponents)}, {}};
  for (const StressVoigt& s : fields.cauchy_stress_Pa) sigma.values.insert(sigma.values.end(), s.data(), s.data() + 6);
  d.cell_data.push_back(std::move(sigma));
  d.cell_data.push_back({"von_mises_stress", 1, {}, fields.von_mises_Pa});
  d.cell_data.push_back({"J", 1, {}, fields.J});
  d.field_data.push_back({"load_fraction", 1, {}, {r.load_fraction}});
  d.string_fields = {{"displacement_unit", {"mm"}},
                     {"stress_unit", {"Pa"}},
                     {"solver_converged", {r.converged ? "true" : "false"}},
                     {"solver_message", {r.message}}};
  return d;
}

}  // namespace

nlohmann::json solver_json(const SolveResult& r) {
  nlohmann::json steps = nlohmann::json::array();
  int cut = 0;
  for (const StepRecord& s : r.steps) {
    steps.push_back(step_json(s));
    cut += s.accepted ? 0 : 1;
  }
  return {{"name", "built-in (total Lagrangian, Newton, load stepping)"},
          {"linear_solver", r.linear_solver},
          {"formulation", r.formulation},
          {"threads", r.threads},
          {"free_dofs", r.free_dofs},
          {"converged", r.converged},
          {"message", r.message},
          {"load_fraction", r.load_fraction},
          {"increments_attempted", r.steps.size()},
          {"increments_cut_back", cut},
          {"total_iterations", r.total_iterations},
          {"factorisations", r.factorisations},
          {"shifted_factorisations", r.shifted_factorisations},
          {"failed_factorisations", r.failed_factorisations},
          {"preconditioned_cg_iterations", r.linear_iterations},
          {"lowest_eigenvalue_iterations", r.eigenvalue_iterations},
          {"cg_preconditioner", r.cg_preconditioner},
          {"tangent_assemblies", r.tangent_assemblies},
          {"force_assemblies", r.force_assemblies},
          {"assembly_seconds", r.assembly_seconds},
          {"linear_solve_seconds", r.linear_solve_seconds},
          {"factorisation_seconds", r.factorisation_seconds},
          {"numeric_factorisation", r.numeric_factorisation},
          {"analysis_seconds", r.analysis_seconds},
          {"factor_entries", r.factor_entries},
          {"factor_flops", r.factor_flops},
          {"seconds", r.seconds},
          {"steps", steps}};
}

namespace {

nlohmann::json results_json(const Model& model, const SolveResult& r, const MotionSummary& motion,
                            const CellFields& fields) {
  const double newton = force_from_newton(model.units, 1.0);  // model force units per N
  const Eigen::Vector3d reaction_N = r.total_reaction / newton, weight_N = r.total_load / newton;
  nlohmann::json tissues = nlohmann::json::array();
  for (std::size_t t = 0; t < motion.tissues.size(); ++t) {
    double vm = 0.0, J_min = std::numeric_limits<double>::max(), J_max = std::numeric_limits<double>::lowest();
    for (std::size_t e = 0; e < model.elements.size(); ++e) {
      if (static_cast<std::size_t>(model.tissue_ids[e] - 1) != t) continue;
      vm = std::max(vm, fields.von_mises_Pa[e]);
      J_min = std::min(J_min, fields.J[e]);
      J_max = std::max(J_max, fields.J[e]);
    }
    const TissueMotion& m = motion.tissues[t];
    nlohmann::json j = {{"name", m.name},
                        {"volume_mm3", m.volume_mm3},
                        {"centroid_mm", vec_json(m.centroid_mm)},
                        {"centroid_displacement_mm", vec_json(m.mean_displacement_mm)},
                        {"centroid_displacement_magnitude_mm", m.mean_displacement_mm.norm()},
                        {"max_von_mises_stress_Pa", vm}};
    if (J_min <= J_max) j.update({{"min_J", J_min}, {"max_J", J_max}});  // a tissue without elements has none
    tissues.push_back(j);
  }
  nlohmann::json results = {
      {"load_fraction", r.load_fraction},
      {"node_ids", "1-based: the node ids of model.inp and model.feb = solution.vtu / model.vtu point index + 1"},
      {"max_displacement_mm", motion.max_displacement_mm},
      {"max_displacement_node", motion.max_displacement_node + 1},
      {"tissues", tissues},
      {"total_reaction_N", vec_json(reaction_N)},
      {"total_weight_N", vec_json(weight_N)},
      {"reaction_vs_weight_rel", nullptr},
      {"reaction_vs_weight_rel_definition",
       "|total_reaction + load_fraction * total_weight| / |total_weight| (0 at equilibrium)"}};
  if (motion.max_displacement_node >= 0)
    results["max_displacement_vector_mm"] = vec_json(r.displacements[motion.max_displacement_node] /
                                                length_from_mm(model.units, 1.0));
  if (weight_N.norm() > 0.0)
    results["reaction_vs_weight_rel"] = (reaction_N + r.load_fraction * weight_N).norm() / weight_N.norm();
  return results;
}

std::string summary_text(const nlohmann::json& record) {
  const nlohmann::json& s = record["solver"];
  const nlohmann::json& res = record["results"];
  // The solver's message starts with "converged" on success and says why otherwise.
  std::string t = "\nsolve: " + std::string(s["converged"].get<bool>() ? "" : "DID NOT CONVERGE: ") +
                  s["message"].get<std::string>() + "\n";
  t += "  load fraction " + format_double("%.4g", s["load_fraction"].get<double>()) + " in " +
       std::to_string(s["increments_attempted"].get<int>()) + " increments (" +
       std::to_string(s["increments_cut_back"].get<int>()) + " cut back), " +
       std::to_string(s["total_iterations"].get<int>()) + " Newton iterations, " +
       format_double("%.2f", s["seconds"].get<double>()) + " s, " + s["formulation"].get<std::string>() + ", " +
       s["linear_solver"].get<std::string>() + ", " +
       std::to_string(s["free_dofs"].get<int>()) + " free dofs\n";
  t += "  max displacement " + format_double("%.4f", res["max_displacement_mm"].get<double>()) + " mm at node " +
       std::to_string(res["max_displacement_node"].get<int>()) + " (1-based, the ids of model.inp/model.feb)\n";
  char line[200];
  std::snprintf(line, sizeof line, "  %-10s %12s   %-34s %10s %16s\n", "tissue", "volume mm^3",
                "mean displacement (x, y, z) mm", "|mean| mm", "max vonMises Pa");
  t += line;
  for (const auto& m : res["tissues"]) {
    const auto& d = m["centroid_displacement_mm"];
    std::snprintf(line, sizeof line, "  %-10s %12.1f   (%9.4f, %9.4f, %9.4f)   %10.4f %16.2f\n",
                  m["name"].get<std::string>().c_str(), m["volume_mm3"].get<double>(), d[0].get<double>(),
                  d[1].get<double>(), d[2].get<double>(), m["centroid_displacement_magnitude_mm"].get<double>(),
                  m["max_von_mises_stress_Pa"].get<double>());
    t += line;
  }
  const auto as_vec = [](const nlohmann::json& j) {
    return Eigen::Vector3d(j[0].get<double>(), j[1].get<double>(), j[2].get<double>());
  };
  t += "  total reaction " + vec_text(as_vec(res["total_reaction_N"]), "%.6g") + " N, weight " +
       vec_text(as_vec(res["total_weight_N"]), "%.6g") + " N";
  if (!res["reaction_vs_weight_rel"].is_null())
    t += ", |reaction + load fraction x weight| / |weight| = " +
         format_double("%.2e", res["reaction_vs_weight_rel"].get<double>());
  return t + "\n";
}

}  // namespace

nlohmann::json solve_into(const Model& model, const JobConfig& config, const nlohmann::json& inputs,
                          const std::string& command_line, Progress& progress, OutputDir& out, SolveResult* result,
                          int threads, RunReport* report) {
  const SolveResult r = run_solver(model, threads, progress);
  const double mm_per_length = 1.0 / length_from_mm(model.units, 1.0);
  CellFields fields;
  MotionSummary motion;
  {
    auto stage = progress.stage("stresses and tissue motion");
    fields = cell_fields(model, r.displacements);
    motion = tissue_motion(model, r.displacements);
  }
  const nlohmann::json solver = solver_json(r);
  const nlohmann::json results = results_json(model, r, motion, fields);
  // Everything that goes into a file is checked before the first byte is written.
  require_finite(solver, "solver");
  require_finite(results, "results");
  const ModelVtuData arrays = solution_arrays(r, fields, mm_per_length);
  {
    auto stage = progress.stage("write solution.vtu");
    write_model_vtu(model, out.stage("solution.vtu").string(), arrays);  // refuses non-finite values too
  }
  nlohmann::json record = run_record_common(progress, command_line);
  record["inputs"] = inputs;
  record["config"] = {{"source", config.source}, {"effective_yaml", config.to_yaml()}};
  record["model"] = model_summary_json(model);
  record["units"] = {{"displacement", "mm"},
                     {"stress", "Pa"},
                     {"force", "N"},
                     {"model_units", unit_system_name(model.units)},
                     {"note", "solved in the model's units (" + length_unit(model.units) + ", " +
                                  stress_unit(model.units) + ", " + force_unit(model.units) + "), reported converted"}};
  record["solver"] = solver;
  record["results"] = results;
  record["outputs"] = {{"solution", out.final_path("solution.vtu").string()},
                       {"record", out.final_path("solve.json").string()}};
  require_finite(record, "");
  write_text_file(out.stage("solve.json"), record.dump(2) + "\n");
  std::cout << summary_text(record);
  if (report) {
    std::vector<Eigen::Vector3d> u_mm(r.displacements.size());
    for (std::size_t i = 0; i < u_mm.size(); ++i) u_mm[i] = r.displacements[i] * mm_per_length;
    report->add_solve(model, u_mm, record, "deformed by gravity");
    report->add_table("Solve summary", summary_text(record));
  }
  if (result) *result = r;
  return record;
}

}  // namespace tissuemesh::app
