// report.html of a run (docs/report.md): each command's outputs add what they have to one
// HtmlReport — the mesh and its quality, a solve's displacement and residuals, the CalculiX
// comparison, the prone-to-supine shapes — and the command stages the page with the other files.
#pragma once

#include "core/model.h"
#include "core/output_dir.h"
#include "core/tet_mesh.h"
#include "core/tri_surface.h"
#include "report/html_report.h"

#include <nlohmann/json.hpp>

#include <Eigen/Core>

#include <optional>
#include <string>
#include <vector>

namespace tissuemesh::app {

/// The page of one run, or nothing with --no-html.
class RunReport {
 public:
  RunReport(bool enabled, const std::string& title, const std::string& command_line);
  bool enabled() const { return page_.has_value(); }

  /// A mesh run: the 3D scene of `mesh` (unless one is set), quality histograms, volume errors,
  /// Table 1 (surface pipeline), the approach corridor and junction curves when `record` has them,
  /// report.txt, versions and config.
  void add_mesh(const TetMesh& mesh, const nlohmann::json& record, const std::string& text);
  /// A solve of `model`: its scene with the displacement (`u_mm` per model node, mm) and the
  /// tumour centroid's path, residual history, stage times. `label` names the displacement. The
  /// first solve of a run is the one shown: later calls do nothing.
  void add_solve(const Model& model, const std::vector<Eigen::Vector3d>& u_mm, const nlohmann::json& record,
                 const std::string& label);
  /// prone2supine: supine shape coloured by the displacement from prone, the tumour centroid's
  /// prone -> reference -> supine path, the iteration history.
  void add_prone2supine(const Model& model, const std::vector<Eigen::Vector3d>& prone,
                        const std::vector<Eigen::Vector3d>& reference, const std::vector<Eigen::Vector3d>& supine,
                        const nlohmann::json& record);
  /// The surface pipeline's junction curves (where three or more regions meet) over the scene.
  void add_junctions(const TriSurface& surface);
  /// The 3D scene and quality histograms of `mesh` alone (cross-checks of a mesh).
  void add_mesh_view(const TetMesh& mesh);
  /// A record as indented JSON (long records cut, saying so).
  void add_record_table(const std::string& title, const nlohmann::json& record);
  void add_table(const std::string& title, const std::string& text);
  /// The stage times to plot: those of `record`'s "timings" (each record holds every stage so far).
  void note_timings(const nlohmann::json& record);

  /// A sweep's summary.json: the sensitivity of each output to each parameter.
  void add_sweep_summary(const nlohmann::json& summary);

  /// The page (empty when disabled). Throws OutputError when a browser library is missing.
  std::string html() const;
  /// Stages DIR/report.html. Throws OutputError when a browser library is missing.
  void stage_into(OutputDir& out) const;

 private:
  void add_quality_once(const TetMesh& mesh);
  std::optional<HtmlReport> page_;
  bool quality_added_ = false;
  nlohmann::json timings_ = nlohmann::json::object();
};

/// Throws OutputError (before any long work) when report.html cannot be written because a browser
/// library is missing, naming it and the package; does nothing when `enabled` is false.
void require_report_assets(bool enabled);

/// The linear corner mesh of `model` (model node order): what its scene draws.
TetMesh corner_mesh(const Model& model);

}  // namespace tissuemesh::app
