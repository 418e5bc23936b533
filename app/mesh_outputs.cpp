#include "app/mesh_outputs.h"

#include "app/cli_support.h"
#include "core/errors.h"
#include "core/surface_vtp.h"
#include "core/vtu_io.h"
#include "pipeline/mesh_job.h"
#include "pipeline/mesh_report.h"
#include "pipeline/surface_report.h"
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

/// A mesh that fails a conformity count is not written: only the reports (which name the counts
/// and where the defects are) are committed, and the run fails.
[[noreturn]] void fail_nonconforming(OutputDir& out, const ConformityReport& conformity) {
  out.commit();
  throw MeshingError("the tet mesh does not conform (" + std::to_string(conformity.degenerate_tets) +
                     " degenerate, " + std::to_string(conformity.inverted_tets) + " inverted tets, " +
                     std::to_string(conformity.nonmanifold_boundary_edges) + " non-manifold boundary edges, " +
                     std::to_string(conformity.faces_shared_by_more_than_two) + " faces in > 2 tets, " +
                     std::to_string(conformity.duplicate_node_groups) + " duplicate node groups, " +
                     std::to_string(conformity.orphan_nodes) + " orphan nodes); mesh.vtu not written, " +
                     "report.txt and report.json in " + out.final_path("").string() + " say where");
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
               const nlohmann::json& inputs, const std::string& cmd, Progress& progress, OutputDir& out,
               RunReport* report) {
  const MeshJobResult result = run_mesh_job(labels, image_name, config, progress);
  const bool conforming = result.conformity.conforming();
  if (conforming) {
    auto stage = progress.stage("write mesh.vtu");
    write_vtu(result.meshing.mesh, out.stage("mesh.vtu").string());
  }
  const std::string text = mesh_job_text(result);
  nlohmann::json record = mesh_record(labels, config, inputs, cmd, progress);
  record["result"] = mesh_job_json(result);
  record["outputs"] = {{"report_text", out.final_path("report.txt").string()}};
  if (conforming) record["outputs"]["mesh"] = out.final_path("mesh.vtu").string();
  write_text(out.stage("report.json"), record.dump(2) + "\n");
  write_text(out.stage("report.txt"), text);
  std::cout << "\n" << text;
  if (!conforming) fail_nonconforming(out, result.conformity);
  if (report) report->add_mesh(result.meshing.mesh, record, text);
  return result.meshing.mesh;
}

void surface_into(const LabelImage& labels, const std::string& image_name, const MeshConfig& config,
                  const nlohmann::json& inputs, const std::string& cmd, Progress& progress, OutputDir& out,
               RunReport* report) {
  const SurfaceJobResult result = run_surface_job(labels, image_name, config, progress);
  const bool write_mesh = result.volume && result.volume->conformity.conforming();
  {
    auto stage = progress.stage(write_mesh ? "write surface.vtp, junctions.vtp, mesh.vtu" : "write surface.vtp, junctions.vtp");
    write_surface_vtp(result.surface(), out.stage("surface.vtp").string());
    write_junctions_vtp(result.surface(), out.stage("junctions.vtp").string());
    if (write_mesh) write_vtu(result.volume->meshing.mesh, out.stage("mesh.vtu").string());
  }
  const std::string text = surface_job_text(result);
  nlohmann::json record = mesh_record(labels, config, inputs, cmd, progress);
  record["result"] = surface_job_json(result);
  record["outputs"] = {{"surface", out.final_path("surface.vtp").string()},
                       {"junctions", out.final_path("junctions.vtp").string()},
                       {"report_text", out.final_path("report.txt").string()}};
  if (write_mesh) record["outputs"]["mesh"] = out.final_path("mesh.vtu").string();
  std::cout << "\n" << text;
  if (!result.checks.valid())
    throw MeshingError(std::string(result.remesh ? "the remeshed" : "the extracted") +
                       " surface fails its checks (see the table above); no output written");
  write_text(out.stage("report.json"), record.dump(2) + "\n");
  write_text(out.stage("report.txt"), text);
  if (result.volume && !write_mesh) fail_nonconforming(out, result.volume->conformity);
  if (report && write_mesh) {
    report->add_mesh(result.volume->meshing.mesh, record, text);
    report->add_junctions(result.surface());
  }
  if (!result.volume_refused.empty()) {
    out.commit();
    throw MeshingError("no tet mesh: " + result.volume_refused + "; report.txt and report.json in " +
                       out.final_path("").string());
  }
}

}  // namespace tissuemesh::app
