// Black-box tests of the tissuemesh program: the commands a user types and what they leave.
#include "cli/cli_runner.h"
#include "image/image_io.h"
#include "support/test_helpers.h"
#include "support/test_paths.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <fstream>

using namespace tissuemesh;
using test::files_below;
using test::read_file;
using test::run_cli;

namespace {

// The shared nested spheres (labels 1 and 2 in background 0), meshed in about a second.
void write_spheres(const std::filesystem::path& path) { write_nifti(test::nested_spheres(), path.string()); }

void write_spheres_config(const std::filesystem::path& path) {
  std::ofstream(path) << "tissues:\n  - {name: shell, labels: [1]}\n  - {name: core, labels: [2]}\n"
                         "direct: {facet_size_mm: 2, cell_size_mm: 3, refine_tissue: ''}\n";
}

}  // namespace

TEST(Cli, HelpAndVersionExitZero) {
  const auto dir = test::scratch_dir();
  auto r = run_cli("--help", dir);
  EXPECT_EQ(r.exit_code, 0);
  for (const char* cmd : {"demo", "phantom", "mesh", "info"}) EXPECT_NE(r.out.find(cmd), std::string::npos) << cmd;
  r = run_cli("mesh --help", dir);
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_NE(r.out.find("--config"), std::string::npos);
  EXPECT_EQ(run_cli("--version", dir).exit_code, 0);
}

TEST(Cli, UsageErrorsExitTwo) {
  const auto dir = test::scratch_dir();
  EXPECT_EQ(run_cli("", dir).exit_code, 2);
  EXPECT_EQ(run_cli("frobnicate", dir).exit_code, 2);
  EXPECT_EQ(run_cli("mesh labels.nii.gz", dir).exit_code, 2);  // -c missing
}

TEST(Cli, MeshWritesMeshReportAndRecord) {
  const auto dir = test::scratch_dir();
  write_spheres(dir / "spheres.nii.gz");
  write_spheres_config(dir / "spheres.yaml");
  const auto r = run_cli("mesh spheres.nii.gz -c spheres.yaml -o out", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(files_below(dir / "out"),
            (std::vector<std::string>{"mesh.vtu", "report.html", "report.json", "report.txt"}));
  // One progress line per stage with its time.
  EXPECT_NE(r.out.find("refine (CGAL Mesh_3) done in"), std::string::npos) << r.out;
  // Not a terminal: plain lines, never a bar's carriage returns.
  EXPECT_EQ(r.out.find('\r'), std::string::npos);
  ASSERT_EQ(run_cli("mesh spheres.nii.gz -c spheres.yaml -o plain --no-html", dir).exit_code, 0);
  EXPECT_EQ(files_below(dir / "plain"), (std::vector<std::string>{"mesh.vtu", "report.json", "report.txt"}));
  const auto report = nlohmann::json::parse(read_file(dir / "out/report.json"));
  EXPECT_TRUE(report["result"]["conforming"].get<bool>());
  EXPECT_GT(report["result"]["tets"].get<int>(), 1000);
  EXPECT_EQ(report["result"]["tissues"], (nlohmann::json{"shell", "core"}));
  EXPECT_TRUE(report["inputs"]["labels"].get<std::string>().find("spheres.nii.gz") != std::string::npos);
  EXPECT_TRUE(report["config"]["effective_yaml"].get<std::string>().find("facet_size_mm: 2") != std::string::npos);
  EXPECT_TRUE(report["versions"].contains("CGAL"));
  EXPECT_GT(report["timings"].size(), 3u);
  EXPECT_GT(report["peak_memory_mib"].get<double>(), 0.0);
  // `info` on the result reports the same mesh.
  const auto info = run_cli("info out/mesh.vtu --json", dir);
  ASSERT_EQ(info.exit_code, 0) << info.err;
  const auto j = nlohmann::json::parse(info.out);
  EXPECT_EQ(j["tets"], report["result"]["tets"]);
  EXPECT_TRUE(j["conformity"]["conforming"].get<bool>());
}

TEST(Cli, MeshIsDeterministic) {
  const auto dir = test::scratch_dir();
  write_spheres(dir / "spheres.nii.gz");
  write_spheres_config(dir / "spheres.yaml");
  ASSERT_EQ(run_cli("mesh spheres.nii.gz -c spheres.yaml -o a", dir).exit_code, 0);
  ASSERT_EQ(run_cli("mesh spheres.nii.gz -c spheres.yaml -o b", dir).exit_code, 0);
  EXPECT_EQ(read_file(dir / "a/mesh.vtu"), read_file(dir / "b/mesh.vtu"));
}

TEST(Cli, PrintConfigShowsEveryKey) {
  const auto dir = test::scratch_dir();
  const auto r = run_cli("mesh x.nii -c '" + test::config_path("breast-generic.yaml") + "' --print-config", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* key : {"pipeline:", "tissues:", "facet_distance_mm:", "sliver_bound_deg:", "exude:"})
    EXPECT_NE(r.out.find(key), std::string::npos) << key;
}

TEST(Cli, PhantomKindsAndNoBackground) {
  const auto dir = test::scratch_dir();
  const auto r = run_cli("phantom --kind folded-layers --no-background --seed 2 --out f.nii.gz", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const LabelImage img = read_label_image((dir / "f.nii.gz").string());
  const auto counts = img.label_counts();
  EXPECT_EQ(counts.count(0), 0u) << "no background";
  EXPECT_EQ(counts.size(), 7u) << "six layers and the lesion";
  EXPECT_NE(read_file(dir / "f.nii.gz.json").find("kind: folded-layers"), std::string::npos);
  // Breast-only options on another kind: a bad-input exit naming them.
  const auto bad = run_cli("phantom --kind fragmented-breast --spacing 1,1,1 --out g.nii.gz", dir);
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("--spacing"), std::string::npos) << bad.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "g.nii.gz"));
  for (const char* config : {"hard-breast.yaml", "hard-breast-no-background.yaml", "hard-breast-no-background-surface.yaml",
                             "folded-layers.yaml", "folded-layers-surface.yaml"}) {
    const auto p = run_cli("mesh x.nii -c '" + test::config_path(config) + "' --print-config", dir);
    EXPECT_EQ(p.exit_code, 0) << config << ": " << p.err;
    EXPECT_NE(p.out.find("kind: "), std::string::npos) << config;
  }
}

TEST(Cli, PhantomIsByteIdenticalForTheSameSeedAndInfoDescribesIt) {
  const auto dir = test::scratch_dir();
  ASSERT_EQ(run_cli("phantom --out a.nii.gz --seed 3", dir).exit_code, 0);
  ASSERT_EQ(run_cli("phantom --out b.nii.gz --seed 3", dir).exit_code, 0);
  ASSERT_EQ(run_cli("phantom --out c.nii.gz --seed 4", dir).exit_code, 0);
  EXPECT_EQ(read_file(dir / "a.nii.gz"), read_file(dir / "b.nii.gz"));
  EXPECT_NE(read_file(dir / "a.nii.gz"), read_file(dir / "c.nii.gz"));
  EXPECT_TRUE(std::filesystem::exists(dir / "a.nii.gz.json"));
  const auto info = run_cli("info a.nii.gz", dir);
  ASSERT_EQ(info.exit_code, 0) << info.err;
  EXPECT_NE(info.out.find("spacing 0.7 x 0.7 x 1.5 mm"), std::string::npos) << info.out;
  EXPECT_NE(info.out.find("orientation RAS"), std::string::npos) << info.out;
}
