#include "report/record_charts.h"

#include "quality/mesh_quality.h"

#include <cmath>
#include <cstdio>
#include <limits>

namespace tissuemesh {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

double number(const nlohmann::json& j) { return j.is_number() ? j.get<double>() : kNaN; }

std::string bin_label(double lo, double hi, const char* fmt) {
  char buf[48];
  std::snprintf(buf, sizeof buf, fmt, lo, hi);
  return buf;
}

/// Per-tissue volume errors of a record's quality block ({"tissues": [{name, id, volume_error_rel}]}).
void add_volume_error_chart(HtmlReport& report, const nlohmann::json& quality, const std::string& title) {
  if (!quality.contains("tissues")) return;
  ChartSpec c{"volume_error", title, "bar", "tissue", "meshed - voxel volume (% of voxel volume)", false, false, {}, {}};
  ChartDataset d{"volume error", {}, "#4477aa"};
  for (const auto& t : quality["tissues"]) {
    c.labels.push_back(t.value("name", std::string("?")));
    d.values.push_back(100.0 * number(t.value("volume_error_rel", nlohmann::json())));
  }
  c.datasets.push_back(d);
  report.add_chart(c);
}

}  // namespace

void add_quality_charts(HtmlReport& report, const TetMesh& mesh) {
  const std::size_t tissues = mesh.num_tissues();
  // The dihedral histogram of the quality report (the same bins as report.json's).
  const QualityReport quality = compute_quality(mesh);
  std::vector<std::vector<double>> ratios(tissues, std::vector<double>(20, 0.0));
  for (std::size_t t = 0; t < mesh.tets.size(); ++t) {
    const auto& c = mesh.tets[t];
    const TetShape s = tet_shape(mesh.points[static_cast<std::size_t>(c[0])], mesh.points[static_cast<std::size_t>(c[1])],
                                 mesh.points[static_cast<std::size_t>(c[2])], mesh.points[static_cast<std::size_t>(c[3])]);
    const std::size_t tissue = static_cast<std::size_t>(mesh.tissue_ids[t] - 1);
    ratios[tissue][std::min<std::size_t>(19, static_cast<std::size_t>(std::max(0.0, s.radius_ratio) / 0.05))] += 1;
  }
  const DihedralHistogram& bins = quality.total.dihedral_histogram;
  ChartSpec a{"dihedral_histogram", "Dihedral angles (6 per tet)", "bar", "dihedral angle (deg)", "angles", false, true, {}, {}};
  for (std::size_t i = 0; i < bins.counts.size(); ++i)
    a.labels.push_back(bin_label(bins.bin_width_deg * static_cast<double>(i), bins.bin_width_deg * static_cast<double>(i + 1), "%.0f-%.0f"));
  ChartSpec r{"radius_ratio_histogram", "Radius ratio 3r/R per tet (1 = regular)", "bar", "radius ratio", "tets", false, true, {}, {}};
  for (int i = 0; i < 20; ++i) r.labels.push_back(bin_label(0.05 * i, 0.05 * (i + 1), "%.2f-%.2f"));
  for (std::size_t i = 0; i < tissues; ++i) {
    const std::string color = tissue_color(mesh.tissue_names[i], static_cast<int>(i + 1));
    const auto& counts = quality.tissues[i].dihedral_histogram.counts;
    a.datasets.push_back({mesh.tissue_names[i], std::vector<double>(counts.begin(), counts.end()), color});
    r.datasets.push_back({mesh.tissue_names[i], ratios[i], color});
  }
  report.add_chart(a);
  report.add_chart(r);
}

void add_mesh_record_charts(HtmlReport& report, const nlohmann::json& record) {
  if (!record.contains("result")) return;
  const nlohmann::json& result = record["result"];
  if (result.contains("quality")) add_volume_error_chart(report, result["quality"], "Tissue volume against the voxel volume");
  if (result.contains("volume_mesh") && result["volume_mesh"].contains("quality"))
    add_volume_error_chart(report, result["volume_mesh"]["quality"], "Tissue volume of the tet mesh against the voxel volume");
  if (result.contains("table1_quality")) {
    const nlohmann::json& q = result["table1_quality"];
    // Alqaoud et al., Table 1: the decimated surfaces of 21K and 2.1K vertices.
    ChartSpec angles{"table1_angles", "Table 1: triangle angles (higher is better)", "bar", "", "deg", false, false,
                     {"average min angle", "min angle"}, {}};
    angles.datasets = {{"this run", {number(q["average_min_angle_deg"]), number(q["min_angle_deg"])}, "#22883c"},
                       {"paper 21K", {49.0487, 26.5}, "#bbbbbb"},
                       {"paper 2.1K", {48.0243, 28.5458}, "#7a7a7a"}};
    ChartSpec shape{"table1_shape", "Table 1: triangle shape quality Q (1 = equilateral)", "bar", "", "Q", false, false,
                    {"Q average", "Q min"}, {}};
    shape.datasets = {{"this run", {number(q["q_average"]), number(q["q_min"])}, "#22883c"},
                      {"paper 21K", {0.860981, 0.412079}, "#bbbbbb"},
                      {"paper 2.1K", {0.848394, 0.486425}, "#7a7a7a"}};
    report.add_chart(angles);
    report.add_chart(shape);
  }
}

void add_solve_record_charts(HtmlReport& report, const nlohmann::json& record, const std::string& id,
                             const std::string& title) {
  const nlohmann::json* solver = record.contains("solver") ? &record["solver"] : nullptr;
  if (!solver || !solver->contains("steps")) return;
  ChartSpec c{id, title, "line", "increment.iteration", "residual norm (N)", true, false, {}, {}};
  ChartDataset accepted{"accepted increments", {}, "#4477aa"};
  ChartDataset cut{"cut-back increments", {}, "#ee6677"};
  int increment = 0;
  for (const auto& step : (*solver)["steps"]) {
    ++increment;
    const bool ok = step.value("accepted", false);
    int iteration = 0;
    for (const auto& r : step["residual_norms"]) {
      c.labels.push_back(std::to_string(increment) + "." + std::to_string(++iteration));
      const double v = number(r) > 0 ? number(r) : kNaN;
      accepted.values.push_back(ok ? v : kNaN);
      cut.values.push_back(ok ? kNaN : v);
    }
  }
  if (c.labels.empty()) return;
  c.datasets.push_back(accepted);
  bool any_cut = false;
  for (double v : cut.values) any_cut = any_cut || std::isfinite(v);
  if (any_cut) c.datasets.push_back(cut);
  report.add_chart(c);
}

void add_prone2supine_record_charts(HtmlReport& report, const nlohmann::json& record) {
  if (!record.contains("reference_state")) return;
  const nlohmann::json& ref = record["reference_state"];
  ChartSpec c{"reference_iterations", "Reference state: prone shape mismatch per forward solve", "line",
              "forward solve (0 = naive reversal)", "max node mismatch (mm)", true, false, {}, {}};
  ChartDataset d{"mismatch", {}, "#aa3377"};
  ChartDataset tol{"tolerance", {}, "#9a9a9a"};
  for (const auto& it : ref["iterations"]) {
    c.labels.push_back(std::to_string(it.value("iteration", 0)));
    d.values.push_back(number(it.value("mismatch_mm", nlohmann::json())));
    tol.values.push_back(number(ref.value("tolerance_mm", nlohmann::json())));
  }
  if (c.labels.empty()) return;
  c.datasets = {d, tol};
  report.add_chart(c);
}

void add_sweep_summary_charts(HtmlReport& report, const nlohmann::json& summary) {
  if (!summary.contains("outputs")) return;
  int n = 0;
  for (const auto& o : summary["outputs"]) {
    if (!o.contains("src")) continue;
    const std::string name = o.value("name", std::string("output"));
    ChartSpec c{"sensitivity_" + std::to_string(++n), "Sensitivity of " + name, "bar", "parameter",
                "index (-1 to 1)", false, false, {}, {}};
    ChartDataset src{"standardised regression coefficient", {}, "#4477aa"};
    ChartDataset first{"Sobol' first order", {}, "#22883c"};
    ChartDataset total{"Sobol' total", {}, "#ccbb44"};
    for (const auto& [parameter, value] : o["src"].items()) {
      c.labels.push_back(parameter);
      src.values.push_back(number(value));
      if (o.contains("sobol_first")) {
        first.values.push_back(number(o["sobol_first"].value(parameter, nlohmann::json())));
        total.values.push_back(number(o["sobol_total"].value(parameter, nlohmann::json())));
      }
    }
    c.datasets.push_back(src);
    if (!first.values.empty()) {
      c.datasets.push_back(first);
      c.datasets.push_back(total);
    }
    report.add_chart(c);
  }
}

void add_timing_chart(HtmlReport& report, const nlohmann::json& record, const std::string& id, const std::string& title) {
  if (!record.contains("timings")) return;
  ChartSpec c{id, title, "hbar", "", "seconds", false, false, {}, {}};
  ChartDataset d{"wall time (s)", {}, "#66aacc"};
  for (const auto& t : record["timings"]) {
    c.labels.push_back(t.value("stage", std::string("?")));
    d.values.push_back(number(t.value("seconds", nlohmann::json())));
  }
  if (c.labels.empty()) return;
  c.datasets.push_back(d);
  report.add_chart(c);
}

}  // namespace tissuemesh
