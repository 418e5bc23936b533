// report.html's data (report/): the scene of a mesh is the mesh's geometry (closed, outward tissue
// boundaries whose enclosed volumes are the tissue volumes), thinning keeps the page under its cap,
// the page carries the node coordinates exactly (as float32) and is the same bytes every time, the
// plots count what the mesh holds, and the progress bar says how far and how long.
#include "core/errors.h"
#include "core/progress_bar.h"
#include "report/html_report.h"
#include "report/record_charts.h"
#include "report/report_scene.h"
#include "support/model_fixture.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <map>
#include <numeric>

namespace tissuemesh {
namespace {

/// Volume enclosed by triangles (divergence theorem): positive for a closed outward surface.
double enclosed_volume(const std::vector<Eigen::Vector3d>& nodes, const std::vector<std::array<int, 3>>& faces) {
  double v = 0;
  for (const auto& f : faces)
    v += nodes[static_cast<std::size_t>(f[0])].dot(nodes[static_cast<std::size_t>(f[1])].cross(nodes[static_cast<std::size_t>(f[2])])) / 6.0;
  return v;
}

/// Every edge used exactly once in each direction: a closed, consistently oriented surface.
bool closed_and_oriented(const std::vector<std::array<int, 3>>& faces) {
  std::map<std::pair<int, int>, int> directed;
  for (const auto& f : faces)
    for (int k = 0; k < 3; ++k) ++directed[{f[k], f[(k + 1) % 3]}];
  for (const auto& [edge, n] : directed) {
    const auto back = directed.find({edge.second, edge.first});
    if (n != 1 || back == directed.end() || back->second != 1) return false;
  }
  return true;
}

std::vector<unsigned char> decode_base64(const std::string& text) {
  static const std::string alphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::vector<unsigned char> out;
  unsigned buffer = 0;
  int bits = 0;
  for (char c : text) {
    if (c == '=') break;
    buffer = (buffer << 6) | static_cast<unsigned>(alphabet.find(c));
    bits += 6;
    if (bits >= 8) {
      bits -= 8;
      out.push_back(static_cast<unsigned char>((buffer >> bits) & 0xff));
    }
  }
  return out;
}

nlohmann::json page_data(const std::string& html) {
  const std::string start = "<script type=\"application/json\" id=\"report-data\">";
  const std::size_t a = html.find(start);
  const std::size_t b = html.find("</script>", a);
  EXPECT_NE(a, std::string::npos);
  return nlohmann::json::parse(html.substr(a + start.size(), b - a - start.size()));
}

TEST(ReportScene, EachTissueBoundaryIsClosedOutwardAndEnclosesTheTissueVolume) {
  const TetMesh mesh = test::block_mesh();
  const ReportScene s = scene_of_mesh(mesh);
  ASSERT_EQ(s.tissue_faces.size(), 3u);
  const double expected[] = {800, 600, 600};
  for (std::size_t t = 0; t < 3; ++t) {
    EXPECT_TRUE(closed_and_oriented(s.tissue_faces[t])) << mesh.tissue_names[t];
    EXPECT_NEAR(enclosed_volume(s.nodes, s.tissue_faces[t]), expected[t], 1e-9) << mesh.tissue_names[t];
  }
  EXPECT_TRUE(closed_and_oriented(s.outer_faces));
  EXPECT_NEAR(enclosed_volume(s.nodes, s.outer_faces), 2000.0, 1e-9);
  EXPECT_EQ(s.tets.size(), mesh.tets.size());
  ASSERT_TRUE(s.clip_at_mm.has_value());  // through the tumour's centroid: x in [14, 20]
  EXPECT_NEAR((*s.clip_at_mm - Eigen::Vector3d(17, 5, 5)).norm(), 0.0, 1e-9);
  for (float a : s.tet_min_dihedral_deg) EXPECT_NEAR(a, 45.0, 1e-4);  // every Kuhn tet: 45, 60 and 90 degrees
}

TEST(ReportScene, ThinningKeepsThePageUnderItsCapAndSaysSo) {
  const ReportScene full = scene_of_mesh(test::block_mesh(2));  // 12,000 tets
  const std::size_t cap = scene_page_bytes(full) / 2;
  ReportScene s = full;
  const std::string note = fit_scene(s, cap);
  EXPECT_LE(scene_page_bytes(s), cap);
  EXPECT_NE(note.find("one tet in"), std::string::npos) << note;
  EXPECT_LT(s.tets.size(), full.tets.size());
  EXPECT_GT(s.tets.size(), 0u);
  for (const auto& t : s.tets)
    for (int v : t) EXPECT_LT(static_cast<std::size_t>(v), s.nodes.size());
  // The surfaces are untouched: still closed around the same volumes.
  EXPECT_NEAR(enclosed_volume(s.nodes, s.outer_faces), 2000.0, 1e-9);

  ReportScene tiny = full;
  const std::size_t small_cap = scene_page_bytes(full) / 40;
  const std::string simplified = fit_scene(tiny, small_cap);
  EXPECT_LE(scene_page_bytes(tiny), small_cap);
  EXPECT_TRUE(tiny.tets.empty());
  EXPECT_NE(simplified.find("simplified"), std::string::npos) << simplified;
  ReportScene same = full;
  EXPECT_EQ(fit_scene(same, scene_page_bytes(full)), "");  // nothing to do at the cap
}

TEST(HtmlReport, ThePageCarriesTheNodesAndIsTheSameEveryTime) {
  if (std::getenv("TISSUEMESH_JS_DIR") == nullptr && !std::ifstream("/usr/share/javascript/three/three.min.js"))
    GTEST_SKIP() << "libjs-three not installed";
  const TetMesh mesh = test::block_mesh();
  HtmlReport page("block </script> test", "tissuemesh test");
  page.set_scene(scene_of_mesh(mesh));
  add_quality_charts(page, mesh);
  page.add_table("text with </script><b>", "a < b");
  const std::string html = page.html();
  EXPECT_EQ(html, page.html());
  // Only the page's own five scripts end: nothing in the data or the tables closes one early.
  std::size_t closers = 0;
  for (std::size_t at = html.find("</script"); at != std::string::npos; at = html.find("</script", at + 1)) ++closers;
  EXPECT_EQ(closers, 5u);
  const nlohmann::json data = page_data(html);
  EXPECT_EQ(data["tables"][0]["title"], "text with </script><b>");
  const auto bytes = decode_base64(data["scene"]["nodes"].get<std::string>());
  ASSERT_EQ(bytes.size(), 12 * mesh.points.size());
  std::vector<float> xyz(bytes.size() / 4);
  std::memcpy(xyz.data(), bytes.data(), bytes.size());
  for (std::size_t i = 0; i < mesh.points.size(); ++i)
    for (int a = 0; a < 3; ++a) EXPECT_EQ(xyz[3 * i + static_cast<std::size_t>(a)], static_cast<float>(mesh.points[i][a]));
  EXPECT_EQ(data["scene"]["tissues"].size(), 3u);
  EXPECT_EQ(data["charts"].size(), 2u);
}

TEST(HtmlReport, AMissingBrowserLibraryIsNamed) {
  setenv("TISSUEMESH_JS_DIR", "/nonexistent/javascript", 1);
  HtmlReport page("t", "c");
  try {
    (void)page.html();
    ADD_FAILURE() << "expected OutputError";
  } catch (const OutputError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/javascript/three/three.min.js"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("libjs-three"), std::string::npos) << e.what();
  }
  unsetenv("TISSUEMESH_JS_DIR");
}

TEST(RecordCharts, HistogramsCountEveryAngleAndEveryTet) {
  const TetMesh mesh = test::block_mesh();
  HtmlReport page("t", "c");
  add_quality_charts(page, mesh);
  ASSERT_EQ(page.charts().size(), 2u);
  const ChartSpec& angles = page.charts()[0];
  const ChartSpec& ratios = page.charts()[1];
  std::map<int, std::size_t> tets_of;
  for (int id : mesh.tissue_ids) ++tets_of[id];
  for (std::size_t t = 0; t < 3; ++t) {
    const auto& a = angles.datasets[t].values;
    const auto& r = ratios.datasets[t].values;
    EXPECT_EQ(std::accumulate(a.begin(), a.end(), 0.0), 6.0 * static_cast<double>(tets_of[static_cast<int>(t + 1)]));
    EXPECT_EQ(std::accumulate(r.begin(), r.end(), 0.0), static_cast<double>(tets_of[static_cast<int>(t + 1)]));
    // A Kuhn tet has two 45-degree angles (bin 45-50), one of 60 (60-65) and three of 90 (90-95).
    const double n = static_cast<double>(tets_of[static_cast<int>(t + 1)]);
    for (std::size_t b = 0; b < a.size(); ++b)
      EXPECT_EQ(a[b], b == 9 ? 2 * n : b == 12 ? n : b == 18 ? 3 * n : 0.0) << "bin " << b;
  }
}

TEST(RecordCharts, ResidualHistoryFromASolveRecord) {
  const nlohmann::json record = {{"solver", {{"steps", {{{"accepted", true}, {"residual_norms", {1.0, 1e-3, 1e-9}}},
                                                         {{"accepted", false}, {"residual_norms", {2.0, 5.0}}}}}}}};
  HtmlReport page("t", "c");
  add_solve_record_charts(page, record, "residuals", "r");
  ASSERT_EQ(page.charts().size(), 1u);
  const ChartSpec& c = page.charts()[0];
  EXPECT_EQ(c.labels, (std::vector<std::string>{"1.1", "1.2", "1.3", "2.1", "2.2"}));
  ASSERT_EQ(c.datasets.size(), 2u);  // accepted and cut back
  EXPECT_EQ(c.datasets[0].values[2], 1e-9);
  EXPECT_TRUE(std::isnan(c.datasets[0].values[3]));
  EXPECT_EQ(c.datasets[1].values[4], 5.0);
  EXPECT_TRUE(c.log_y);
}

TEST(ProgressBar, SaysHowFarAndHowLongIsLeft) {
  const std::string half = progress_bar_line(0.5, 10.0, "round 3/6", 200);
  EXPECT_NE(half.find("[############............]"), std::string::npos) << half;
  EXPECT_NE(half.find(" 50%"), std::string::npos) << half;
  EXPECT_NE(half.find("~10 s left"), std::string::npos) << half;
  EXPECT_NE(half.find("round 3/6"), std::string::npos) << half;
  const std::string done = progress_bar_line(1.0, 4.0, "x", 200);
  EXPECT_EQ(done.find("left"), std::string::npos) << done;
  EXPECT_NE(done.find("100%"), std::string::npos) << done;
  EXPECT_LE(progress_bar_line(0.3, 1.0, std::string(300, 'y'), 60).size(), 59u);
}

}  // namespace
}  // namespace tissuemesh
