// `tissuemesh demo` end to end on the default phantom: the acceptance figures of the direct
// pipeline, measured on what the demo leaves on disk. Slow (~10 s); CI runs it.
#include "cli/cli_runner.h"
#include "core/vtu_io.h"
#include "mesher/conformity.h"
#include "support/test_paths.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

using namespace tissuemesh;

TEST(Demo, PhantomMeshIsConformingWithFaithfulVolumes) {
  const auto dir = test::scratch_dir();
  const auto r = test::run_cli("demo --out demo", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(test::files_below(dir / "demo"),
            (std::vector<std::string>{"export.json", "mesh.vtu", "model.feb", "model.inp", "model.msh", "model.scn",
                                      "model.vtk", "model.vtu", "phantom.nii.gz", "report.json", "report.txt"}));
  for (const char* stage : {"generate phantom done in", "refine (CGAL Mesh_3) done in", "exude slivers done in"})
    EXPECT_NE(r.out.find(stage), std::string::npos) << stage;

  // Conformity recomputed independently of the report, from the written file.
  const TetMesh mesh = read_vtu((dir / "demo/mesh.vtu").string());
  const ConformityReport c = check_conformity(mesh);
  EXPECT_EQ(c.faces_shared_by_more_than_two, 0u);
  EXPECT_EQ(c.duplicate_node_groups, 0u);
  EXPECT_EQ(c.inverted_tets, 0u);
  EXPECT_EQ(c.degenerate_tets, 0u);
  EXPECT_EQ(c.orphan_nodes, 0u);
  EXPECT_EQ(c.nonmanifold_boundary_edges, 0u);
  EXPECT_EQ(mesh.tissue_names, (std::vector<std::string>{"fat", "fgt", "tumor", "skin", "muscle"}));

  const auto report = nlohmann::json::parse(test::read_file(dir / "demo/report.json"));
  const auto& result = report["result"];
  for (const auto& t : result["quality"]["tissues"]) {
    const std::string name = t["name"];
    // Acceptance bounds of the direct pipeline: 3% per tissue, 5% for the small tumour.
    const double bound = name == "tumor" ? 0.05 : 0.03;
    EXPECT_LT(std::abs(t["volume_error_rel"].get<double>()), bound) << name;
  }
  EXPECT_TRUE(result["components_not_meshed"].empty()) << result["components_not_meshed"].dump();
  // Acceptance: minimum dihedral >= 5 degrees and under 0.1% of tets below 10 degrees.
  const auto& total = result["quality"]["total"];
  EXPECT_GE(total["min_dihedral_deg"].get<double>(), 5.0);
  EXPECT_LT(total["tets_below_10deg"].get<double>() / total["tets"].get<double>(), 0.001);
}

TEST(Demo, SameRunSameMesh) {
  const auto dir = test::scratch_dir();
  ASSERT_EQ(test::run_cli("demo --out a", dir).exit_code, 0);
  ASSERT_EQ(test::run_cli("demo --out b", dir).exit_code, 0);
  EXPECT_EQ(test::read_file(dir / "a/mesh.vtu"), test::read_file(dir / "b/mesh.vtu"));
  EXPECT_EQ(test::read_file(dir / "a/phantom.nii.gz"), test::read_file(dir / "b/phantom.nii.gz"));
  for (const char* f : {"model.feb", "model.inp", "model.scn", "model.vtk", "model.vtu", "model.msh"})
    EXPECT_EQ(test::read_file(dir / "a" / f), test::read_file(dir / "b" / f)) << f;
}
