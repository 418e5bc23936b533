#include "app/mesh_outputs.h"

#include "app/cli_support.h"
#include "core/errors.h"
#include "core/surface_vtp.h"
#include "core/vtu_io.h"
#include "pipeline/mesh_job.h"
#include "pipeline/mesh_report.h"
#include "pipeline/surface_job.h"

#include <fstream>
#include <iostream>

namespace tissuemesh::app {

namespace {
void write_text(const std::filesystem::path& path, const std::string& text) {
  std::ofstream f(path);
  f << text;
  if (!f.flush()) throw OutputError(path.string() + ": cannot write");
}

/// The run record every mesh run writes: inputs, effective config, image summary, result, outputs.
nlohmann::json mesh_record(const LabelImage& labels, const MeshConfig& config, const nlohmann::json& inputs,
                           const std::string& cmd, Progress& progress) {
  nlohmann::json record = run_record_common(progress, cmd);
  record["inputs"] = inputs;
  record["config"] = {{"source", config.source}, {"effective_yaml", config.to_yaml()}};
  record["image"] = image_summary_json(labels);
  return record;
}
}  // namespace

TetMesh mesh_into(const LabelImage& labels, const std::string& image_name, const MeshConfig& config,
               const nlohmann::json& inputs, const std::string& cmd, Progress& progress, OutputDir& out) {
  const MeshJobResult result = run_mesh_job(labels, image_name, config, progress);
  {
    auto stage = progress.stage("write mesh.vtu");
    write_vtu(result.meshing.mesh, out.stage("mesh.vtu").string());
  }
  const std::string text = mesh_job_text(result);
  nlohmann::json record = mesh_record(labels, config, inputs, cmd, progress);
  record["result"] = mesh_job_json(result);
  record["outputs"] = {{"mesh", out.final_path("mesh.vtu").string()},
                       {"report_text", out.final_path("report.txt").string()}};
  write_text(out.stage("report.json"), record.dump(2) + "\n");
  write_text(out.stage("report.txt"), text);
  std::cout << "\n" << text;
  return result.meshing.mesh;
}

void surface_into(const LabelImage& labels, const std::string& image_name, const MeshConfig& config,
                  const nlohmann::json& inputs, const std::string& cmd, Progress& progress, OutputDir& out) {
  const SurfaceJobResult result = run_surface_job(labels, image_name, config, progress);
  {
    auto stage = progress.stage(result.volume ? "write surface.vtp, junctions.vtp, mesh.vtu" : "write surface.vtp, junctions.vtp");
    write_surface_vtp(result.surface(), out.stage("surface.vtp").string());
    write_junctions_vtp(result.surface(), out.stage("junctions.vtp").string());
    if (result.volume) write_vtu(result.volume->meshing.mesh, out.stage("mesh.vtu").string());
  }
  const std::string text = surface_job_text(result);
  nlohmann::json record = mesh_record(labels, config, inputs, cmd, progress);
  record["result"] = surface_job_json(result);
  record["outputs"] = {{"surface", out.final_path("surface.vtp").string()},
                       {"junctions", out.final_path("junctions.vtp").string()},
                       {"report_text", out.final_path("report.txt").string()}};
  if (result.volume) record["outputs"]["mesh"] = out.final_path("mesh.vtu").string();
  std::cout << "\n" << text;
  if (!result.checks.valid())
    throw MeshingError(std::string(result.remesh ? "the remeshed" : "the extracted") +
                       " surface fails its checks (see the table above); no output written");
  write_text(out.stage("report.json"), record.dump(2) + "\n");
  write_text(out.stage("report.txt"), text);
}

}  // namespace tissuemesh::app
