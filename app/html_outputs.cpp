#include "app/html_outputs.h"

#include "core/errors.h"
#include "report/record_charts.h"
#include "report/report_assets.h"

#include <fstream>

namespace tissuemesh::app {

namespace {

Eigen::Vector3d vec(const nlohmann::json& j) { return {j[0].get<double>(), j[1].get<double>(), j[2].get<double>()}; }

void add_record_meta(HtmlReport& page, const nlohmann::json& record) {
  if (record.contains("versions")) {
    std::map<std::string, std::string> versions;
    for (const auto& [k, v] : record["versions"].items()) versions[k] = v.is_string() ? v.get<std::string>() : v.dump();
    page.set_versions(versions);
  }
  if (record.contains("config") && record["config"].contains("effective_yaml"))
    page.set_config_yaml(record["config"]["effective_yaml"].get<std::string>());
}

}  // namespace

TetMesh corner_mesh(const Model& model) {
  TetMesh mesh;
  mesh.points.assign(model.nodes.begin(), model.nodes.begin() + model.num_corner_nodes);
  mesh.tets.reserve(model.elements.size());
  for (const auto& e : model.elements) mesh.tets.push_back({e[0], e[1], e[2], e[3]});
  mesh.tissue_ids = model.tissue_ids;
  mesh.tissue_names = model.tissue_names;
  return mesh;
}

RunReport::RunReport(bool enabled, const std::string& title, const std::string& command_line) {
  if (enabled) page_.emplace(title, command_line);
}

void RunReport::add_mesh(const TetMesh& mesh, const nlohmann::json& record, const std::string& text) {
  if (!page_) return;
  if (!page_->scene()) page_->set_scene(scene_of_mesh(mesh));
  ReportScene& scene = *page_->scene();
  if (record.contains("result") && record["result"].contains("approach")) {
    const nlohmann::json& a = record["result"]["approach"];
    scene.corridor = ReportCorridor{vec(a["entry_mm"]), vec(a["target_centroid_mm"]), a.value("corridor_radius_mm", 10.0)};
  }
  add_quality_once(mesh);
  add_mesh_record_charts(*page_, record);
  note_timings(record);
  page_->add_table("Mesh report (report.txt)", text);
  add_record_meta(*page_, record);
}

void RunReport::add_solve(const Model& model, const std::vector<Eigen::Vector3d>& u_mm, const nlohmann::json& record,
                          const std::string& label) {
  if (!page_ || (page_->scene() && !page_->scene()->displacement_mm.empty())) return;
  const TetMesh mesh = corner_mesh(model);
  // The solve's scene is in model node order, which may differ from mesh.vtu's: it replaces the
  // mesh's (same geometry).
  ReportScene scene = scene_of_mesh(mesh);
  if (page_->scene()) {
    scene.corridor = page_->scene()->corridor;
    scene.junction_segments = page_->scene()->junction_segments;
  }
  scene.displacement_mm.assign(u_mm.begin(), u_mm.begin() + model.num_corner_nodes);
  scene.displacement_label = label;
  if (const int tumour = tumour_tissue_id(mesh.tissue_names)) {
    std::vector<Eigen::Vector3d> deformed(mesh.points.size());
    for (std::size_t i = 0; i < deformed.size(); ++i) deformed[i] = mesh.points[i] + scene.displacement_mm[i];
    const auto from = tissue_centroid(mesh, tumour, mesh.points), to = tissue_centroid(mesh, tumour, deformed);
    if (from && to) scene.paths.push_back({"tumour centroid", {*from, *to}});
  }
  page_->set_scene(std::move(scene));
  add_quality_once(mesh);
  add_solve_record_charts(*page_, record, "residuals", "Newton residual per iteration (built-in solve)");
  note_timings(record);
  add_record_meta(*page_, record);
}

void RunReport::add_prone2supine(const Model& model, const std::vector<Eigen::Vector3d>& prone,
                                 const std::vector<Eigen::Vector3d>& reference, const std::vector<Eigen::Vector3d>& supine,
                                 const nlohmann::json& record) {
  if (!page_) return;
  add_prone2supine_record_charts(*page_, record);
  note_timings(record);
  add_record_meta(*page_, record);
  // In the demo the gravity solve's view stays; on its own, the page shows the supine shape.
  if (page_->scene() && !page_->scene()->displacement_mm.empty()) return;
  TetMesh mesh = corner_mesh(model);
  const std::size_t n = mesh.points.size();
  for (std::size_t i = 0; i < n; ++i) mesh.points[i] = prone[i];
  ReportScene scene = scene_of_mesh(mesh);
  for (std::size_t i = 0; i < n; ++i) scene.displacement_mm.push_back(supine[i] - prone[i]);
  scene.displacement_label = "supine, coloured by the motion from prone";
  if (const int tumour = tumour_tissue_id(mesh.tissue_names)) {
    const auto a = tissue_centroid(mesh, tumour, prone), b = tissue_centroid(mesh, tumour, reference),
               c = tissue_centroid(mesh, tumour, supine);
    if (a && b && c) scene.paths.push_back({"tumour centroid prone -> reference -> supine", {*a, *b, *c}});
  }
  page_->set_scene(std::move(scene));
  add_quality_once(mesh);
  add_solve_record_charts(*page_, nlohmann::json{{"solver", record.value("supine_solve", nlohmann::json::object())}},
                          "supine_residuals", "Newton residual per iteration (supine solve)");
}

void RunReport::add_junctions(const TriSurface& surface) {
  if (!page_ || !page_->scene()) return;
  for (const auto& line : surface.junctions)
    for (std::size_t i = 0; i + 1 < line.size(); ++i)
      page_->scene()->junction_segments.push_back(
          {surface.points[static_cast<std::size_t>(line[i])], surface.points[static_cast<std::size_t>(line[i + 1])]});
}

void RunReport::add_quality_once(const TetMesh& mesh) {
  if (quality_added_) return;
  add_quality_charts(*page_, mesh);
  quality_added_ = true;
}

void RunReport::add_mesh_view(const TetMesh& mesh) {
  if (!page_) return;
  if (!page_->scene()) page_->set_scene(scene_of_mesh(mesh));
  add_quality_once(mesh);
}

void RunReport::add_record_table(const std::string& title, const nlohmann::json& record) {
  if (!page_) return;
  constexpr std::size_t kMax = 200000;
  std::string text = record.dump(2);
  if (text.size() > kMax) text = text.substr(0, kMax) + "\n... (cut; the JSON file holds all of it)";
  page_->add_table(title, text);
  add_record_meta(*page_, record);
  note_timings(record);
}

void RunReport::add_table(const std::string& title, const std::string& text) {
  if (page_) page_->add_table(title, text);
}

void RunReport::note_timings(const nlohmann::json& record) {
  if (record.contains("timings")) timings_ = record;
}

void RunReport::add_sweep_summary(const nlohmann::json& summary) {
  if (page_) add_sweep_summary_charts(*page_, summary);
}

std::string RunReport::html() const {
  if (!page_) return {};
  // The stage times of the run so far (the last record holds every stage), last among the plots.
  HtmlReport page = *page_;
  add_timing_chart(page, timings_, "timings", "Time per stage");
  return page.html();
}

void RunReport::stage_into(OutputDir& out) const {
  if (!page_) return;
  const std::string html = this->html();
  const auto path = out.stage("report.html");
  std::ofstream f(path, std::ios::binary);
  f << html;
  if (!f.flush()) throw OutputError(path.string() + ": cannot write");
}

void require_report_assets(bool enabled) {
  if (enabled) (void)load_report_assets();
}

}  // namespace tissuemesh::app
