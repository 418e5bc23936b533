#include "app/export_outputs.h"

#include "app/cli_support.h"
#include "core/errors.h"
#include "core/model_builder.h"
#include "core/vtu_io.h"
#include "fe_export/registry.h"

#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <sstream>

namespace tissuemesh::app {

nlohmann::json model_summary_json(const Model& model) {
  nlohmann::json tissues = nlohmann::json::array();
  std::vector<double> volume(model.tissue_names.size(), 0.0);
  std::vector<int> count(model.tissue_names.size(), 0);
  for (std::size_t e = 0; e < model.elements.size(); ++e) {
    volume[model.tissue_ids[e] - 1] += element_volume(model, e);
    ++count[model.tissue_ids[e] - 1];
  }
  double weight_N = 0.0;
  const double g = model.gravity.acceleration_m_s2.norm();
  for (std::size_t t = 0; t < model.tissue_names.size(); ++t) {
    const MaterialSpec& m = model.materials[t];
    const double mass_kg = m.density_kg_m3 * volume[t] * 1e-9;
    weight_N += mass_kg * g;
    tissues.push_back({{"name", model.tissue_names[t]},
                       {"elements", count[t]},
                       {"volume_mm3", volume[t]},
                       {"mass_kg", mass_kg},
                       {"law", material_law_name(m.law)},
                       {"shear_modulus_Pa", m.mu_Pa},
                       {"bulk_modulus_Pa", m.K_Pa},
                       {"poisson_ratio", m.poisson_ratio()},
                       {"density_kg_m3", m.density_kg_m3},
                       {"source", m.source}});
  }
  nlohmann::json sets = nlohmann::json::array();
  for (const NodeSet& s : model.node_sets)
    sets.push_back({{"name", s.name},
                    {"nodes", s.nodes.size()},
                    {"constraint", s.constraint == Constraint::Fixed ? "fixed" : "sliding"},
                    {"selection", s.selection}});
  nlohmann::json faces = nlohmann::json::array();
  for (const FaceSet& s : model.face_sets)
    faces.push_back({{"name", s.name}, {"faces", s.faces.size()}, {"selection", s.selection}});
  const Eigen::Vector3d& a = model.gravity.acceleration_m_s2;
  return {{"element", model.order == ElementOrder::Linear ? "tet4" : "tet10"},
          {"nodes", model.nodes.size()},
          {"corner_nodes", model.num_corner_nodes},
          {"elements", model.elements.size()},
          {"units", unit_system_name(model.units)},
          {"tissues", tissues},
          {"node_sets", sets},
          {"face_sets", faces},
          {"gravity", {{"direction", model.gravity.name}, {"acceleration_m_s2", {a[0], a[1], a[2]}}}},
          {"total_weight_N", weight_N}};
}

namespace {

std::string summary_text(const Model& model, const nlohmann::json& summary) {
  std::ostringstream s;
  s << "model: " << summary["elements"].get<std::size_t>() << " " << summary["element"].get<std::string>()
    << " elements, " << model.nodes.size() << " nodes, units " << unit_system_name(model.units) << " ("
    << length_unit(model.units) << ", " << stress_unit(model.units) << ", " << density_unit(model.units) << ")\n";
  s << "  tissue      elements   volume mm^3   law                        mu Pa      K Pa    rho kg/m^3\n";
  for (const auto& t : summary["tissues"]) {
    s << "  " << std::left << std::setw(10) << t["name"].get<std::string>() << std::right << std::setw(10)
      << t["elements"].get<int>() << std::setw(14) << std::fixed << std::setprecision(0)
      << t["volume_mm3"].get<double>() << "   " << std::left << std::setw(24) << t["law"].get<std::string>()
      << std::right << std::setw(9) << std::setprecision(1) << t["shear_modulus_Pa"].get<double>() << std::setw(10)
      << std::setprecision(0) << t["bulk_modulus_Pa"].get<double>() << std::setw(12)
      << t["density_kg_m3"].get<double>() << "\n";
  }
  for (const NodeSet& n : model.node_sets)
    s << "  node set " << n.name << ": " << n.nodes.size() << " nodes, "
      << (n.constraint == Constraint::Fixed ? "fixed" : "sliding") << " (" << n.selection << ")\n";
  for (const FaceSet& f : model.face_sets)
    s << "  face set " << f.name << ": " << f.faces.size() << " faces (" << f.selection << ")\n";
  const Eigen::Vector3d& a = model.gravity.acceleration_m_s2;
  s << std::setprecision(3) << "  gravity " << model.gravity.name << ": (" << a[0] << ", " << a[1] << ", " << a[2]
    << ") m/s^2 (LPS); total weight " << std::setprecision(4) << summary["total_weight_N"].get<double>() << " N\n";
  return s.str();
}

void write_text(const std::filesystem::path& path, const std::string& text) {
  std::ofstream f(path);
  f << text;
  if (!f.flush()) throw OutputError(path.string() + ": cannot write");
}

}  // namespace

Model build_job_model(const TetMesh& mesh, const JobConfig& config, Progress& progress) {
  if (!config.has_materials)
    throw InputError(config.source + ": has no `materials:` section (every tissue needs a law, its parameters "
                                     "and a density; e.g. `materials: {preset: materials/ucl-niftysim-invivo.yaml}`)");
  auto stage = progress.stage("build model");
  Model model = build_model(mesh, config.model, config.materials.tissues, config.materials.source);
  model.title = "tissuemesh model";
  return model;
}

TetMesh read_job_mesh(const std::string& mesh_path, Progress& progress) {
  auto stage = progress.stage("read " + mesh_path);
  return read_vtu(mesh_path);
}

nlohmann::json job_inputs(const std::string& mesh_path, const JobConfig& config) {
  return {{"mesh", std::filesystem::absolute(mesh_path).string()},
          {"config", std::filesystem::absolute(config.source).string()}};
}

JobModel read_job_model(const std::string& mesh_path, const JobConfig& config, Progress& progress) {
  const TetMesh mesh = read_job_mesh(mesh_path, progress);
  JobModel job;
  job.inputs = job_inputs(mesh_path, config);
  job.model = build_job_model(mesh, config, progress);
  return job;
}

nlohmann::json export_into(const Model& model, const JobConfig& config, const std::vector<std::string>& formats,
                           const nlohmann::json& inputs, const std::string& command_line, Progress& progress,
                           OutputDir& out) {
  std::vector<const ExportFormat*> chosen;
  for (const std::string& name : formats) chosen.push_back(&export_format_named(name));
  const nlohmann::json summary = model_summary_json(model);
  nlohmann::json files = nlohmann::json::array();
  nlohmann::json notes = nlohmann::json::array();
  for (const ExportFormat* format : chosen) {
    auto stage = progress.stage("write " + format->default_file);
    if (format->name == "sofa") out.stage(std::filesystem::path(format->default_file).stem().string() + ".vtk");
    const ExportResult r = export_model(model, *format, out.stage(format->default_file).string(), config.exports);
    for (const std::string& f : r.files) files.push_back(std::filesystem::path(f).filename().string());
    for (const std::string& n : r.notes) {
      notes.push_back(format->name + ": " + n);
      stage.note(format->name + ": " + n);
    }
  }
  nlohmann::json record = run_record_common(progress, command_line);
  record["inputs"] = inputs;
  record["config"] = {{"source", config.source}, {"effective_yaml", config.to_yaml()}};
  record["model"] = summary;
  record["files"] = files;
  record["notes"] = notes;
  write_text(out.stage("export.json"), record.dump(2) + "\n");
  std::cout << "\n" << summary_text(model, summary);
  return record;
}

}  // namespace tissuemesh::app
