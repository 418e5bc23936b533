// `tissuemesh demo` end to end on the default phantom: the acceptance figures of the direct
// pipeline and of the built-in solver against CalculiX (max nodal difference <= 1% of the max
// displacement, tet4 on the default phantom, tet10 on the coarse one; docs/verification.md,
// "Solver: agreement with CalculiX"), measured on what the demo leaves on disk. Slow (the default
// demo's CalculiX run takes ~2 min, the coarse tet10 one ~75 s); CI runs them.
#include "cli/cli_runner.h"
#include "core/vtu_io.h"
#include "quality/conformity.h"
#include "solver_check/calculix_run.h"
#include "support/test_paths.h"
#include "support/tolerances.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <iostream>

using namespace tissuemesh;

namespace {

/// Every file the demo writes besides calculix/ (whose files are CalculiX's own).
std::vector<std::string> demo_files(bool with_check) {
  std::vector<std::string> files{"export.json", "mesh.vtu",       "model.feb",   "model.inp",  "model.msh",
                                 "model.scn",   "model.vtk",      "model.vtu",   "phantom.nii.gz", "report.html", "report.json",
                                 "report.txt",  "solution.vtu",   "solve.json"};
  if (with_check) files.insert(files.begin(), "check.json");
  return files;
}

std::vector<std::string> outside_calculix(const std::vector<std::string>& files) {
  std::vector<std::string> kept;
  for (const std::string& f : files)
    if (f.rfind("calculix/", 0) != 0) kept.push_back(f);
  return kept;
}

/// The CalculiX comparison the demo in `dir` recorded: printed, and within the acceptance bound.
void expect_agreement_with_calculix(const std::filesystem::path& dir, const std::string& what) {
  for (const char* f : {"check.json", "calculix/model.inp", "calculix/model.dat"})
    EXPECT_TRUE(std::filesystem::exists(dir / f)) << f;
  const auto record = nlohmann::json::parse(test::read_file(dir / "check.json"));
  const auto& c = record["comparison"];
  const auto& model = record["model"];
  std::cout << "[ demo     ] " << what << " (" << model["elements"] << " " << model["element"].get<std::string>()
            << ", " << model["nodes"] << " nodes): max |u| CalculiX " << c["max_u_mm_calculix"] << " mm, built-in "
            << c["max_u_mm_builtin"] << " mm; difference max " << 100 * c["max_diff_rel"].get<double>() << " %, mean "
            << 100 * c["mean_diff_rel"].get<double>() << " % of max |u| (node " << c["max_diff_node"]
            << "); CalculiX " << record["calculix"]["seconds"] << " s, built-in " << record["builtin"]["seconds"]
            << " s (" << record["builtin"]["linear_solver"] << ")\n";
  EXPECT_TRUE(record["builtin"]["converged"].get<bool>());
  EXPECT_TRUE(record["builtin"]["reused_solve"].get<bool>()) << "the phantom's laws need no replacing: one solve";
  EXPECT_GT(c["max_u_mm_calculix"].get<double>(), 0.0);
  EXPECT_LE(c["max_diff_rel"].get<double>(), test::kCalculixSolutionRel);
  EXPECT_LE(record["equilibrium"]["imbalance_rel"].get<double>(), test::kSolverDefaultEquilibriumRel);
}

}  // namespace

TEST(Demo, PhantomMeshIsConformingWithFaithfulVolumes) {
  const auto dir = test::scratch_dir();
  if (find_calculix().empty()) GTEST_SKIP() << "ccx not found (set TISSUEMESH_CCX or put ccx on PATH)";
  const auto r = test::run_cli("demo --out demo", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(outside_calculix(test::files_below(dir / "demo")), demo_files(true));
  for (const char* stage : {"generate phantom done in", "refine (CGAL Mesh_3) done in", "exude slivers done in",
                            "run CalculiX done in", "max displacement", "tumour centroid displacement",
                            "reaction vs weight", "difference vs CalculiX"})
    EXPECT_NE(r.out.find(stage), std::string::npos) << stage;
  // Agreement with CalculiX on the default phantom, tet4.
  expect_agreement_with_calculix(dir / "demo", "default phantom");

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
  // Every tet at 10 degrees or more: the sliver smoothing slides the vertices of slivers on curved
  // interfaces over the image's interfaces (without it the phantom keeps five, down to 6.9).
  const auto& total = result["quality"]["total"];
  EXPECT_GE(total["min_dihedral_deg"].get<double>(), 10.0);
  EXPECT_EQ(total["tets_below_10deg"].get<int>(), 0);
}

TEST(Demo, SameRunSameMesh) {
  const auto dir = test::scratch_dir();
  const auto a = test::run_cli("demo --out a --skip-calculix", dir);
  ASSERT_EQ(a.exit_code, 0) << a.err;
  ASSERT_EQ(test::run_cli("demo --out b --skip-calculix", dir).exit_code, 0);
  EXPECT_NE(a.out.find("CalculiX cross-check skipped (--skip-calculix)"), std::string::npos);
  EXPECT_EQ(test::files_below(dir / "a"), demo_files(false));
  EXPECT_EQ(test::read_file(dir / "a/mesh.vtu"), test::read_file(dir / "b/mesh.vtu"));
  EXPECT_EQ(test::read_file(dir / "a/phantom.nii.gz"), test::read_file(dir / "b/phantom.nii.gz"));
  // solution.vtu too: the built-in solve is deterministic (static_solver.h: fixed summation order).
  for (const char* f : {"model.feb", "model.inp", "model.scn", "model.vtk", "model.vtu", "model.msh", "solution.vtu"})
    EXPECT_EQ(test::read_file(dir / "a" / f), test::read_file(dir / "b" / f)) << f;
}

TEST(Demo, CoarseTet10AgreesWithCalculix) {
  // Agreement with CalculiX with quadratic elements: the coarse phantom
  // (configs/phantom-coarse.yaml) as tet10 (~15K nodes; CalculiX ~75 s).
  if (find_calculix().empty()) GTEST_SKIP() << "ccx not found (set TISSUEMESH_CCX or put ccx on PATH)";
  const auto dir = test::scratch_dir();
  const auto r = test::run_cli("demo -c " + test::coarse_config(dir, "tet10") + " --out demo", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto record = nlohmann::json::parse(test::read_file(dir / "demo/check.json"));
  EXPECT_EQ(record["model"]["element"], "tet10");
  expect_agreement_with_calculix(dir / "demo", "coarse phantom");
}
