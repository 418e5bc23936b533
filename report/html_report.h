// HtmlReport: one self-contained HTML page per run (DIR/report.html) that opens offline in any
// browser: a WebGL view of the mesh (tissue surfaces, a clipping plane through the tets, the
// displacement), plots (Chart.js) and the run's tables. three.js, its OrbitControls and Chart.js
// are read from the Debian packages libjs-three and libjs-chart.js (report/report_assets.h) and
// inlined at write time; the mesh goes in as base64 float32/uint32 arrays. The page fetches
// nothing and needs no server.
//
// Deterministic: the same content gives the same bytes (no dates, no random ids).
#pragma once

#include "report/report_scene.h"

#include <cstddef>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace tissuemesh {

struct ChartDataset {
  std::string label;
  std::vector<double> values;   ///< one per chart label; NaN or infinity draws nothing
  std::string color;            ///< CSS colour, e.g. "#4477aa"
};

/// A plot: "bar" (vertical bars), "hbar" (horizontal bars) or "line".
struct ChartSpec {
  std::string id;               ///< unique in the page, [a-z0-9_-]
  std::string title;
  std::string kind = "bar";
  std::string x_title, y_title; ///< axis titles with units
  bool log_y = false;
  bool stacked = false;
  std::vector<std::string> labels;
  std::vector<ChartDataset> datasets;
};

struct HtmlReportOptions {
  /// Largest page before the 3D data is thinned for display (report_scene.h fit_scene), bytes.
  std::size_t size_cap_bytes = 20'000'000;
};

class HtmlReport {
 public:
  HtmlReport(std::string title, std::string command_line);

  /// The 3D view. Without a scene the page has plots and tables only.
  void set_scene(ReportScene scene) { scene_ = std::move(scene); }
  ReportScene* scene() { return scene_ ? &*scene_ : nullptr; }

  void add_chart(ChartSpec chart);
  const std::vector<ChartSpec>& charts() const { return charts_; }
  void add_table(std::string title, std::string preformatted_text);
  void add_note(std::string text);
  void set_versions(std::map<std::string, std::string> versions) { versions_ = std::move(versions); }
  void set_config_yaml(std::string yaml) { config_yaml_ = std::move(yaml); }

  /// The page. Throws OutputError when a browser library is missing (report_assets.h).
  std::string html(const HtmlReportOptions& options = {}) const;

 private:
  std::string title_, command_line_;
  std::optional<ReportScene> scene_;
  std::vector<ChartSpec> charts_;
  std::vector<std::pair<std::string, std::string>> tables_;
  std::vector<std::string> notes_;
  std::map<std::string, std::string> versions_;
  std::string config_yaml_;
};

/// The colour report.html gives tissue `name` (fixed for the usual breast tissues, from a
/// palette by `id` otherwise), "#rrggbb".
std::string tissue_color(const std::string& name, int id);

}  // namespace tissuemesh
