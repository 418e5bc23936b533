#include "report/html_report.h"

#include "report/report_assets.h"

#include <vtkBase64Utilities.h>

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstring>

namespace tissuemesh {

namespace {

template <typename T>
std::string base64(const std::vector<T>& values) {
  const auto* bytes = reinterpret_cast<const unsigned char*>(values.data());
  const std::size_t n = values.size() * sizeof(T);
  std::string out(4 * ((n + 2) / 3) + 4, '\0');
  const auto written = vtkBase64Utilities::Encode(bytes, static_cast<unsigned long>(n),
                                                  reinterpret_cast<unsigned char*>(&out[0]));
  out.resize(static_cast<std::size_t>(written));
  return out;
}

std::vector<float> flatten(const std::vector<Eigen::Vector3d>& v) {
  std::vector<float> out;
  out.reserve(3 * v.size());
  for (const auto& p : v)
    for (int a = 0; a < 3; ++a) out.push_back(static_cast<float>(p[a]));
  return out;
}

template <std::size_t N>
std::vector<std::uint32_t> flatten(const std::vector<std::array<int, N>>& cells) {
  std::vector<std::uint32_t> out;
  out.reserve(N * cells.size());
  for (const auto& c : cells)
    for (int v : c) out.push_back(static_cast<std::uint32_t>(v));
  return out;
}

nlohmann::json point_json(const Eigen::Vector3d& p) { return {p.x(), p.y(), p.z()}; }

nlohmann::json scene_json(const ReportScene& s) {
  nlohmann::json j;
  j["nodes"] = base64(flatten(s.nodes));
  nlohmann::json tissues = nlohmann::json::array();
  for (std::size_t i = 0; i < s.tissue_names.size(); ++i) {
    const int id = static_cast<int>(i + 1);
    tissues.push_back({{"id", id}, {"name", s.tissue_names[i]}, {"color", tissue_color(s.tissue_names[i], id)},
                       {"tris", base64(flatten(s.tissue_faces[i]))}});
  }
  j["tissues"] = tissues;
  j["outer"] = base64(flatten(s.outer_faces));
  if (!s.tets.empty()) {
    j["tets"] = base64(flatten(s.tets));
    j["tet_tissue"] = base64(s.tet_tissue);
    j["tet_quality"] = base64(s.tet_min_dihedral_deg);
  }
  if (!s.displacement_mm.empty()) {
    double max = 0;
    for (const auto& u : s.displacement_mm) max = std::max(max, u.norm());
    j["displacement"] = {{"label", s.displacement_label.empty() ? "displacement" : s.displacement_label},
                         {"data", base64(flatten(s.displacement_mm))},
                         {"max_mm", max}};
  }
  nlohmann::json paths = nlohmann::json::array();
  for (const auto& p : s.paths) {
    nlohmann::json pts = nlohmann::json::array();
    for (const auto& q : p.points) pts.push_back(point_json(q));
    paths.push_back({{"name", p.name}, {"points", pts}});
  }
  j["paths"] = paths;
  if (s.corridor)
    j["corridor"] = {{"entry_mm", point_json(s.corridor->entry_mm)}, {"target_mm", point_json(s.corridor->target_mm)},
                     {"radius_mm", s.corridor->radius_mm}};
  if (!s.junction_segments.empty()) {
    std::vector<Eigen::Vector3d> ends;
    for (const auto& seg : s.junction_segments) {
      ends.push_back(seg[0]);
      ends.push_back(seg[1]);
    }
    j["segments"] = base64(flatten(ends));
  }
  if (s.clip_at_mm) j["clip_at_mm"] = point_json(*s.clip_at_mm);
  return j;
}

nlohmann::json chart_json(const ChartSpec& c) {
  nlohmann::json datasets = nlohmann::json::array();
  for (const auto& d : c.datasets) {
    nlohmann::json values = nlohmann::json::array();
    for (double v : d.values) values.push_back(std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr));
    datasets.push_back({{"label", d.label}, {"data", values}, {"color", d.color}});
  }
  return {{"id", c.id},         {"title", c.title},       {"kind", c.kind},     {"x_title", c.x_title},
          {"y_title", c.y_title}, {"log_y", c.log_y},     {"stacked", c.stacked}, {"labels", c.labels},
          {"datasets", datasets}};
}

/// JSON that may sit inside a <script> element: every '<' (only ever inside strings) escaped.
std::string script_safe(const std::string& json) {
  std::string out;
  out.reserve(json.size());
  for (char ch : json) {
    if (ch == '<') out += "\\u003c";
    else out += ch;
  }
  return out;
}

std::string html_escape(const std::string& text) {
  std::string out;
  for (char ch : text) {
    switch (ch) {
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '&': out += "&amp;"; break;
      case '"': out += "&quot;"; break;
      default: out += ch;
    }
  }
  return out;
}

}  // namespace

HtmlReport::HtmlReport(std::string title, std::string command_line)
    : title_(std::move(title)), command_line_(std::move(command_line)) {}

void HtmlReport::add_chart(ChartSpec chart) { charts_.push_back(std::move(chart)); }
void HtmlReport::add_table(std::string title, std::string text) { tables_.emplace_back(std::move(title), std::move(text)); }
void HtmlReport::add_note(std::string text) { notes_.push_back(std::move(text)); }

std::string HtmlReport::html(const HtmlReportOptions& options) const {
  const ReportAssets assets = load_report_assets();
  nlohmann::json r;
  r["title"] = title_;
  r["command_line"] = command_line_;
  nlohmann::json notes = notes_;
  if (scene_) {
    // The libraries, tables and plots take what they take; the 3D data gets the rest of the cap.
    std::size_t fixed = assets.three_js.size() + assets.orbit_controls_js.size() + assets.chart_js.size() +
                        assets.page_js.size() + assets.page_css.size() + config_yaml_.size() + 200000;
    for (const auto& t : tables_) fixed += t.second.size();
    ReportScene scene = *scene_;
    const std::size_t room = options.size_cap_bytes > fixed ? options.size_cap_bytes - fixed : 0;
    const std::string note = fit_scene(scene, room);
    if (!note.empty()) notes.push_back(note);
    r["scene"] = scene_json(scene);
  }
  r["notes"] = notes;
  nlohmann::json charts = nlohmann::json::array();
  for (const auto& c : charts_) charts.push_back(chart_json(c));
  r["charts"] = charts;
  nlohmann::json tables = nlohmann::json::array();
  for (const auto& t : tables_) tables.push_back({{"title", t.first}, {"text", t.second}});
  r["tables"] = tables;
  r["meta"] = {{"versions", versions_}, {"config_yaml", config_yaml_}};

  std::string page;
  page.reserve(4000000);
  page += "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n";
  page += "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n";
  page += "<meta name=\"generator\" content=\"tissuemesh\">\n<title>" + html_escape(title_) + "</title>\n";
  page += "<style>\n" + assets.page_css + "</style>\n</head>\n<body>\n";
  page += "<header><h1 id=\"title\"></h1><code id=\"cmd\"></code></header>\n";
  page += "<main id=\"main\"><div id=\"errors\" class=\"errors\"></div></main>\n";
  page += "<pre id=\"report-status\" hidden></pre>\n";
  page += "<noscript>This report needs JavaScript for its 3D view and plots.</noscript>\n";
  page += "<script>\n" + assets.three_js + "\n</script>\n";
  page += "<script>\n" + assets.orbit_controls_js + "\n</script>\n";
  page += "<script>\n" + assets.chart_js + "\n</script>\n";
  // Data as JSON for JSON.parse, several times faster to load than the same object as a script.
  page += "<script type=\"application/json\" id=\"report-data\">" + script_safe(r.dump()) + "</script>\n";
  page += "<script>\n" + assets.page_js + "\n</script>\n</body>\n</html>\n";
  return page;
}

std::string tissue_color(const std::string& name, int id) {
  // Hues far apart so that each tissue is told apart in the page and by its browser test.
  if (name == "fat") return "#f0d35a";
  if (name == "fgt" || name == "fibroglandular" || name == "glandular") return "#e0609f";
  if (name == "tumor" || name == "tumour") return "#6a3dc0";
  if (name == "skin") return "#f2a277";
  if (name == "muscle" || name == "pectoral_muscle") return "#b8322a";
  static const char* palette[] = {"#4477aa", "#66ccee", "#22883c", "#ccbb44", "#ee6677", "#aa3377", "#bbbbbb", "#11773c"};
  return palette[static_cast<std::size_t>(id > 0 ? id - 1 : 0) % 8];
}

}  // namespace tissuemesh
