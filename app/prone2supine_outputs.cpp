#include "app/prone2supine_outputs.h"

#include "app/cli_support.h"
#include "app/export_outputs.h"
#include "app/solve_outputs.h"
#include "core/errors.h"
#include "core/unit_system.h"
#include "core/vtu_io.h"
#include "fe_export/registry.h"
#include "fe_export/vtu/write_model_vtu.h"
#include "image/image_io.h"
#include "solver_check/tissue_motion.h"
#include "workflows/label_transfer.h"
#include "workflows/landmarks.h"
#include "workflows/reference_state.h"
#include "workflows/step_models.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>

namespace tissuemesh::app {

namespace {

using Positions = std::vector<Eigen::Vector3d>;

Positions plus(const Positions& a, const Positions& b) {
  Positions out(a.size());
  for (std::size_t v = 0; v < a.size(); ++v) out[v] = a[v] + b[v];
  return out;
}

Positions minus(const Positions& a, const Positions& b) {
  Positions out(a.size());
  for (std::size_t v = 0; v < a.size(); ++v) out[v] = a[v] - b[v];
  return out;
}

double max_norm(const Positions& u, int n) {
  double m = 0.0;
  for (int v = 0; v < n; ++v) m = std::max(m, u[v].norm());
  return m;
}

VtuArray vector_array(const std::string& name, const Positions& values) {
  VtuArray a{name, 3, {"x", "y", "z"}, {}};
  for (const Eigen::Vector3d& v : values) a.values.insert(a.values.end(), v.data(), v.data() + 3);
  return a;
}

Model at(const Model& model, const Positions& nodes) {
  Model m = model;
  m.nodes = nodes;
  return m;
}

// "iteration 3: mismatch 0.1234 mm (best), alpha 0.74, 3 Newton iterations in 1 increment, 0.41 s"
std::string iteration_line(const ReferenceIteration& it) {
  std::string line = "iteration " + std::to_string(it.index) + (it.index == 0 ? " (naive reversal)" : "") + ": ";
  line += it.solved ? "mismatch " + format_double("%.4g", it.mismatch_mm) + " mm" + (it.improved ? " (best)" : "")
                    : std::string("forward solve failed");
  if (it.index > 0) line += ", alpha " + format_double("%.3g", it.alpha);
  line += ", " + std::to_string(it.newton_iterations) + " Newton iterations in " + std::to_string(it.increments) +
          (it.increments == 1 ? " increment" : " increments") + ", " + format_double("%.2f", it.seconds) + " s";
  if (!it.improved) line += " (" + it.note + ")";
  return line;
}

nlohmann::json reference_json(const ReferenceStateResult& r, const Prone2SupineSettings& s) {
  nlohmann::json history = nlohmann::json::array();
  for (const ReferenceIteration& it : r.history) {
    nlohmann::json j = {{"iteration", it.index},          {"alpha", it.alpha},
                        {"solved", it.solved},            {"improved", it.improved},
                        {"newton_iterations", it.newton_iterations}, {"increments", it.increments},
                        {"seconds", it.seconds},          {"note", it.note}};
    j["mismatch_mm"] = it.solved ? nlohmann::json(it.mismatch_mm) : nlohmann::json(nullptr);
    history.push_back(j);
  }
  return {{"method", "fixed-point backward displacement (Sellier 2011), started from naive reversal"},
          {"converged", r.converged},
          {"message", r.message},
          {"tolerance_mm", s.tolerance_mm},
          {"mismatch_mm", r.measured ? nlohmann::json(r.mismatch_mm) : nlohmann::json(nullptr)},
          {"mismatch_definition", "max over mesh nodes of |reference loaded prone - input|, mm"},
          {"best_iteration", r.best_iteration},
          {"forward_solves", r.history.size()},
          {"seconds", r.seconds},
          {"naive_reversal",
           {{"converged", r.reversal.converged},
            {"message", r.reversal.message},
            {"newton_iterations", r.reversal.total_iterations},
            {"seconds", r.reversal.seconds},
            {"mismatch_mm", r.naive_measured ? nlohmann::json(r.naive_mismatch_mm) : nlohmann::json(nullptr)}}},
          {"iterations", history}};
}

/// Per tissue: volume and centroid (geometric, of the configuration) in each configuration.
nlohmann::json tissues_json(const Model& model, const Positions& prone, const Positions& reference,
                            const Positions& supine) {
  const Positions zero(model.nodes.size(), Eigen::Vector3d::Zero());
  const MotionSummary p = tissue_motion(at(model, prone), zero);
  const MotionSummary r = tissue_motion(at(model, reference), zero);
  const MotionSummary s = tissue_motion(at(model, supine), zero);
  nlohmann::json out = nlohmann::json::array();
  for (std::size_t t = 0; t < p.tissues.size(); ++t) {
    const double vp = p.tissues[t].volume_mm3, vr = r.tissues[t].volume_mm3, vs = s.tissues[t].volume_mm3;
    const Eigen::Vector3d motion = s.tissues[t].centroid_mm - p.tissues[t].centroid_mm;
    out.push_back({{"name", model.tissue_names[t]},
                   {"volume_prone_mm3", vp},
                   {"volume_reference_mm3", vr},
                   {"volume_supine_mm3", vs},
                   {"volume_change_reference_vs_prone_rel", vp > 0 ? (vr - vp) / vp : 0.0},
                   {"volume_change_supine_vs_prone_rel", vp > 0 ? (vs - vp) / vp : 0.0},
                   {"centroid_prone_mm", vec_json(p.tissues[t].centroid_mm)},
                   {"centroid_reference_mm", vec_json(r.tissues[t].centroid_mm)},
                   {"centroid_supine_mm", vec_json(s.tissues[t].centroid_mm)},
                   {"centroid_motion_prone_to_supine_mm", vec_json(motion)},
                   {"centroid_motion_prone_to_supine_magnitude_mm", motion.norm()}});
  }
  return out;
}

std::string csv_number(double v) { return format_double("%.6f", v); }

void write_points_csv(const std::filesystem::path& path, const std::vector<Landmark>& points,
                      const std::vector<LandmarkLocation>& where, const Model& model, const Positions& reference,
                      const Positions& supine) {
  std::string text =
      "name,prone_x_mm,prone_y_mm,prone_z_mm,reference_x_mm,reference_y_mm,reference_z_mm,supine_x_mm,supine_y_mm,"
      "supine_z_mm,displacement_mm,element_id,tissue\n";
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Eigen::Vector3d p = points[i].position_mm;
    const Eigen::Vector3d r = landmark_position(where[i], reference), s = landmark_position(where[i], supine);
    text += points[i].name;
    for (const Eigen::Vector3d* x : {&p, &r, &s})
      for (int k = 0; k < 3; ++k) text += "," + csv_number((*x)[k]);
    text += "," + csv_number((s - p).norm()) + "," + std::to_string(where[i].element + 1) + "," +
            model.tissue_names[where[i].tissue - 1] + "\n";
  }
  write_text_file(path, text);
}

const char* const kSupineFormats[] = {"febio", "abaqus", "sofa"};

}  // namespace

Prone2SupineOutcome prone2supine_into(const TetMesh& mesh, const JobConfig& config, const Prone2SupineRequest& request,
                                      const nlohmann::json& inputs, const std::string& command_line,
                                      Progress& progress, OutputDir& out, RunReport* report) {
  const Prone2SupineSettings& p2s = config.prone2supine;
  JobConfig build = config;
  build.model = settings_for_steps(config.model, p2s);  // sliding sets of either step carry normals
  const Model base = build_job_model(mesh, build, progress);
  if (!(base.gravity.acceleration_m_s2.norm() > 0.0))
    throw InputError(config.source + ": model.gravity is none: prone2supine needs the gravity the imaged (prone) "
                                     "shape carries, e.g. `model: {gravity: {direction: prone}}`");
  const Model unloading = unloading_model(base, config.model, p2s);
  const int corners = base.num_corner_nodes;

  // Everything a user can get wrong is checked before the solves.
  std::vector<Landmark> points;
  std::vector<LandmarkLocation> where;
  if (!request.points_path.empty()) {
    auto stage = progress.stage("locate landmarks of " + request.points_path);
    points = read_landmarks_csv(request.points_path);
    where = locate_landmarks(unloading, points);
    stage.note(std::to_string(points.size()) + " landmarks inside the mesh");
  }
  LabelImage prone_labels;
  if (!request.image_path.empty()) {
    auto stage = progress.stage("read " + request.image_path);
    prone_labels = read_label_image(request.image_path);
  }

  ReferenceStateResult ref;
  {
    auto stage = progress.stage("reference state (fixed point, tolerance " + format_double("%g", p2s.tolerance_mm) +
                                " mm, at most " + std::to_string(p2s.max_iterations) + " forward solves)");
    ref = estimate_reference_state(unloading, reference_state_options(p2s, request.threads),
                                   [&](const ReferenceIteration& it) { stage.note(iteration_line(it)); });
    stage.note(ref.message);
  }

  const Model supine = supine_model(base, config.model, p2s, ref.reference_nodes);
  SolveResult sup;
  {
    auto stage = progress.stage(std::string("supine solve (built-in, ") + formulation_name(supine) + ", gravity " +
                                p2s.supine_gravity.direction + ")");
    SolveOptions options;
    options.threads = request.threads;
    int attempt = 0;
    options.on_step = [&](const StepRecord& s) { stage.note(step_line(s, ++attempt), s.accepted ? s.load_fraction : s.load_fraction - s.increment); };
    sup = solve_static(supine, options);
    stage.note(sup.message);
  }

  const double mm_per_length = 1.0 / length_from_mm(supine.units, 1.0);
  Positions u_supine(sup.displacements.size());
  for (std::size_t v = 0; v < u_supine.size(); ++v) u_supine[v] = sup.displacements[v] * mm_per_length;
  const Positions& prone = unloading.nodes;
  const Positions& reference = ref.reference_nodes;
  const Positions supine_nodes = plus(reference, u_supine);
  const Positions prone_check = plus(reference, ref.loaded_displacements_mm);
  const Positions from_prone = minus(supine_nodes, prone);

  // The record, checked finite before any file is written.
  nlohmann::json record = run_record_common(progress, command_line);
  record["inputs"] = inputs;
  record["config"] = {{"source", config.source}, {"effective_yaml", config.to_yaml()}};
  record["model"] = model_summary_json(unloading);
  record["units"] = {{"length", "mm"}, {"note", "positions LPS mm; displacements mm"}};
  record["reference_state"] = reference_json(ref, p2s);
  nlohmann::json supine_solver = solver_json(sup);
  supine_solver.erase("steps");
  record["supine_solve"] = supine_solver;
  record["supine_gravity_m_s2"] = vec_json(supine.gravity.acceleration_m_s2);
  record["tissues"] = tissues_json(base, prone, reference, supine_nodes);
  record["max_displacement_prone_to_reference_mm"] = max_norm(minus(reference, prone), corners);
  record["max_displacement_reference_to_supine_mm"] = max_norm(u_supine, corners);
  record["max_displacement_prone_to_supine_mm"] = max_norm(from_prone, corners);
  nlohmann::json landmarks = nlohmann::json::array();
  for (std::size_t i = 0; i < points.size(); ++i)
    landmarks.push_back({{"name", points[i].name},
                         {"prone_mm", vec_json(points[i].position_mm)},
                         {"reference_mm", vec_json(landmark_position(where[i], reference))},
                         {"supine_mm", vec_json(landmark_position(where[i], supine_nodes))},
                         {"tissue", base.tissue_names[where[i].tissue - 1]}});
  record["landmarks"] = landmarks;
  require_finite(record, "");

  {
    auto stage = progress.stage("write reference.vtu, supine.vtu, prone_check.vtu");
    TetMesh reference_mesh = mesh;
    for (int v = 0; v < corners; ++v) reference_mesh.points[base.mesh_node_of[v]] = reference[v];
    write_vtu(reference_mesh, out.stage("reference.vtu").string());
    ModelVtuData supine_data;
    supine_data.point_data = {vector_array("displacement_from_prone", from_prone),
                              vector_array("displacement_from_reference", u_supine)};
    supine_data.string_fields = {{"displacement_unit", {"mm"}},
                                 {"configuration", {"supine"}},
                                 {"solver_converged", {sup.converged ? "true" : "false"}}};
    write_model_vtu(at(supine, supine_nodes), out.stage("supine.vtu").string(), supine_data);
    ModelVtuData check_data;
    check_data.point_data = {vector_array("displacement", ref.loaded_displacements_mm),
                             vector_array("mismatch", minus(prone_check, prone))};
    check_data.string_fields = {{"displacement_unit", {"mm"}}, {"configuration", {"reference loaded prone"}}};
    write_model_vtu(at(unloading, prone_check), out.stage("prone_check.vtu").string(), check_data);
  }
  nlohmann::json files = {"reference.vtu", "supine.vtu", "prone_check.vtu"};
  for (const char* name : kSupineFormats) {
    const ExportFormat& format = export_format_named(name);
    const std::string file = "supine_model" + std::filesystem::path(format.default_file).extension().string();
    auto stage = progress.stage("write " + file);
    if (format.name == "sofa") out.stage("supine_model.vtk");
    const ExportResult r = export_model(supine, format, out.stage(file).string(), config.exports);
    for (const std::string& f : r.files) files.push_back(std::filesystem::path(f).filename().string());
    for (const std::string& n : r.notes) stage.note(format.name + ": " + n);
  }
  if (!points.empty()) {
    write_points_csv(out.stage("points.csv"), points, where, base, reference, supine_nodes);
    files.push_back("points.csv");
  }
  if (!request.image_path.empty()) {
    auto stage = progress.stage("carry the labels into the supine shape");
    const LabelImage supine_labels = transfer_labels(prone_labels, base, prone, supine_nodes);
    stage.note(std::to_string(supine_labels.dims[0]) + " x " + std::to_string(supine_labels.dims[1]) + " x " +
               std::to_string(supine_labels.dims[2]) + " voxels at the input spacing");
    write_nifti(supine_labels, out.stage("supine_labels.nii.gz").string());
    files.push_back("supine_labels.nii.gz");
  }
  files.push_back("prone2supine.json");
  record["files"] = files;
  write_text_file(out.stage("prone2supine.json"), record.dump(2) + "\n");
  if (report) report->add_prone2supine(base, prone, reference, supine_nodes, record);

  Prone2SupineOutcome outcome;
  outcome.record = record;
  outcome.converged = ref.converged && sup.converged;
  if (!ref.converged) outcome.failure = "reference state: " + ref.message;
  else if (!sup.converged) outcome.failure = "supine solve: " + sup.message;

  // Summary.
  char line[256];
  std::cout << "\nprone to supine" << (outcome.converged ? "" : " (NOT converged: " + outcome.failure + ")") << ":\n";
  std::snprintf(line, sizeof line, "  %-34s %.4g mm after %zu forward solves (naive reversal: %s)\n",
                "reference state mismatch", ref.measured ? ref.mismatch_mm : 0.0, ref.history.size(),
                ref.naive_measured ? (format_double("%.4g", ref.naive_mismatch_mm) + " mm").c_str() : "not measured");
  std::cout << line;
  std::snprintf(line, sizeof line, "  %-34s %.3f mm, reference to supine %.3f mm, prone to supine %.3f mm\n",
                "max displacement prone to reference", record["max_displacement_prone_to_reference_mm"].get<double>(),
                record["max_displacement_reference_to_supine_mm"].get<double>(),
                record["max_displacement_prone_to_supine_mm"].get<double>());
  std::cout << line;
  for (const auto& t : record["tissues"]) {
    const auto& m = t["centroid_motion_prone_to_supine_mm"];
    std::snprintf(line, sizeof line, "  %-10s centroid moves %8.3f mm = (%.3f, %.3f, %.3f) LPS, volume %+.2f %%\n",
                  t["name"].get<std::string>().c_str(), t["centroid_motion_prone_to_supine_magnitude_mm"].get<double>(),
                  m[0].get<double>(), m[1].get<double>(), m[2].get<double>(),
                  100.0 * t["volume_change_supine_vs_prone_rel"].get<double>());
    std::cout << line;
  }
  return outcome;
}

}  // namespace tissuemesh::app
