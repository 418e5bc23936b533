// `tissuemesh check` through the program, on the block of tests/support/model_fixture.h with one
// tissue of each kind of law (a compressible neo-Hookean to be replaced, a Mooney-Rivlin and an
// Ogden kept): --calculix, the built-in solver and CalculiX agree within 1% of the max
// displacement; --tetgen, TetGen's mesh of the same geometry moves the tumor alike; --gmsh, Gmsh's
// gamma and SICN equal ours on every tet. Bad requests and a missing or failing ccx are refused
// with their exit codes and nothing written.
#include "cli/cli_runner.h"
#include "core/vtu_io.h"
#include "quality/mesh_quality.h"
#include "solver_check/calculix_run.h"
#include "support/model_fixture.h"
#include "support/test_paths.h"
#include "support/tolerances.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <random>

using namespace tissuemesh;
using test::files_below;
using test::read_file;
using test::run_cli;

namespace {

class Check : public ::testing::Test {
 protected:
  void SetUp() override {
    dir = test::scratch_dir();
    write_vtu(test::block_mesh(), (dir / "block.vtu").string());
    std::ofstream(dir / "block.yaml") << R"(materials:
  fat: {law: compressible-neo-hookean, mu: 150 Pa, K: 50 kPa, density: 950 kg/m^3}
  fgt: {law: mooney-rivlin, C10: 100 Pa, C01: 50 Pa, K: 60 kPa, density: 1040 kg/m^3}
  tumor: {law: ogden, terms: [{mu: 700 Pa, alpha: 2}, {mu: 200 Pa, alpha: -2}], K: 100 kPa, density: 1060 kg/m^3}
model:
  element: tet4  # the quick check (auto would give tet10: nu = 0.4985); tet10 is checked on the coarse demo
  node_sets: [{name: chest_wall, plane: {point_mm: [0, 10, 0], normal: [0, 1, 0], tolerance_mm: 0.01}}]
)";
  }

  /// Runs `args` with TISSUEMESH_CCX set to `ccx` (restored afterwards).
  test::CliResult run_with_ccx(const std::string& ccx, const std::string& args) {
    const char* old = std::getenv("TISSUEMESH_CCX");
    const std::string saved = old ? old : "";
    ::setenv("TISSUEMESH_CCX", ccx.c_str(), 1);
    const auto r = run_cli(args, dir);
    if (old)
      ::setenv("TISSUEMESH_CCX", saved.c_str(), 1);
    else
      ::unsetenv("TISSUEMESH_CCX");
    return r;
  }

  std::filesystem::path dir;
};

TEST_F(Check, CalculixAndBuiltInAgreeOnTheBlock) {
  if (find_calculix().empty()) GTEST_SKIP() << "ccx not found (set TISSUEMESH_CCX or put ccx on PATH)";
  const auto r = run_cli("check block.vtu -c block.yaml -o out --calculix", dir);
  std::cout << r.out;
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* f : {"check.json", "calculix/model.inp", "calculix/model.dat", "calculix/model.log"})
    EXPECT_TRUE(std::filesystem::exists(dir / "out" / f)) << f;
  for (const std::string& f : files_below(dir / "out"))
    EXPECT_TRUE(f == "check.json" || f == "report.html" || f.rfind("calculix/", 0) == 0) << "unexpected output " << f;

  const auto record = nlohmann::json::parse(read_file(dir / "out/check.json"));
  const auto& c = record["comparison"];
  const double max_rel = c["max_diff_rel"], mean_rel = c["mean_diff_rel"];
  std::cout << "[ check    ] block tet4: max |u| CalculiX " << c["max_u_mm_calculix"] << " mm, built-in "
            << c["max_u_mm_builtin"] << " mm; max diff " << 100 * max_rel << " %, mean diff " << 100 * mean_rel
            << " % of max |u| (node " << c["max_diff_node"] << "); CalculiX " << record["calculix"]["seconds"]
            << " s, built-in " << record["builtin"]["seconds"] << " s\n";
  EXPECT_LE(max_rel, test::kCalculixSolutionRel);
  EXPECT_LE(mean_rel, max_rel);
  EXPECT_GT(c["max_u_mm_calculix"].get<double>(), 0.0);
  EXPECT_GE(c["max_diff_node"].get<int>(), 1);
  EXPECT_LE(c["max_diff_node"].get<int>(), record["model"]["nodes"].get<int>());

  EXPECT_TRUE(record["builtin"]["converged"].get<bool>());
  EXPECT_FALSE(record["builtin"]["reused_solve"].get<bool>());
  EXPECT_EQ(record["calculix"]["exit_code"], 0);
  EXPECT_EQ(record["calculix"]["version"], "2.20") << "Debian's calculix-ccx, the version the README cites";
  EXPECT_EQ(record["calculix"]["inp"], "calculix/model.inp");
  EXPECT_LE(record["equilibrium"]["imbalance_rel"].get<double>(), test::kSolverDefaultEquilibriumRel);
  for (const char* key : {"command_line", "versions", "timings", "inputs", "config", "model"})
    EXPECT_TRUE(record.contains(key)) << key;

  // The compressible fat is checked as NEO HOOKE (noted, and in the deck); Mooney-Rivlin and
  // Ogden are kept.
  std::string notes;
  for (const auto& n : record["notes"]) notes += n.get<std::string>() + "\n";
  EXPECT_NE(notes.find("tissue 'fat': compressible-neo-hookean has no exact CalculiX equivalent"), std::string::npos)
      << notes;
  EXPECT_EQ(notes.find("'fgt'"), std::string::npos) << notes;
  EXPECT_EQ(notes.find("'tumor'"), std::string::npos) << notes;
  EXPECT_NE(r.out.find("compressible-neo-hookean has no exact CalculiX equivalent"), std::string::npos);
  const std::string deck = read_file(dir / "out/calculix/model.inp");
  EXPECT_NE(deck.find("NEO HOOKE"), std::string::npos);
  EXPECT_NE(deck.find("MOONEY-RIVLIN"), std::string::npos);
  EXPECT_NE(deck.find("OGDEN"), std::string::npos);
  const auto& tissues = record["model"]["tissues"];
  EXPECT_EQ(tissues[0]["law"], "neo-hookean") << "the summary is of the model both solvers solved";
  EXPECT_EQ(tissues[1]["law"], "mooney-rivlin");

  // The console: a progress note before CalculiX with the model size, its time after, the table.
  for (const char* needle : {"ccx -i model: 396 nodes, 1500 tet4 elements", "ccx finished in", "max |u| [mm]",
                             "wall time [s]", "% of CalculiX's max |u|", "built-in reaction [N]"})
    EXPECT_NE(r.out.find(needle), std::string::npos) << needle;
}

TEST_F(Check, WithoutACrossCheckIsBadInput) {
  const auto r = run_cli("check block.vtu -c block.yaml -o out", dir);
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("choose one cross-check: --calculix, --tetgen or --gmsh"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "out"));
}

TEST_F(Check, NoCalculixIsBadInputSayingHowToGetIt) {
  const auto r = run_with_ccx((dir / "no-such-ccx").string(), "check block.vtu -c block.yaml -o out --calculix");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  for (const char* needle : {"calculix-ccx", "TISSUEMESH_CCX"})
    EXPECT_NE(r.err.find(needle), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "out"));
}

TEST_F(Check, FailingCalculixIsAnInternalFailureShowingItsLog) {
  // A stand-in ccx that fails the way ccx does: a message on stdout and a non-zero exit code.
  const auto fake = dir / "fake-ccx";
  std::ofstream(fake) << "#!/bin/sh\necho 'CalculiX Version 2.20'\necho '*ERROR reading *MATERIAL: fake failure'\n"
                         "exit 201\n";
  std::filesystem::permissions(fake, std::filesystem::perms::owner_all);
  const auto r = run_with_ccx(fake.string(), "check block.vtu -c block.yaml -o out --calculix");
  EXPECT_EQ(r.exit_code, 1) << r.err;
  for (const char* needle : {"exit code 201", "*ERROR reading *MATERIAL: fake failure"})
    EXPECT_NE(r.err.find(needle), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "out")) << "no partial output";
}

TEST_F(Check, TetgenMeshesTheSameGeometryAndMovesTheTumorAlike) {
  // tet10: with nu ~ 0.4985, tet4 locks, and locking depends on the mesh (measured when TetGen was
  // sized by volume bounds: the tumor's mean displacement 40 % apart between the two tet4 meshes,
  // 3.4 % with tet10; with TetGen sized from the block mesh, tet10: 2.9 %).
  std::string yaml = read_file(dir / "block.yaml");
  yaml.replace(yaml.find("element: tet4"), 13, "element: tet10");
  std::ofstream(dir / "block10.yaml") << yaml;
  const auto r = run_cli("check block.vtu -c block10.yaml -o out --tetgen", dir);
  std::cout << r.out;
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const std::string& f : files_below(dir / "out"))
    EXPECT_TRUE(f == "check.json" || f == "report.html" || f == "mesh_tetgen.vtu") << "unexpected output " << f;
  // Read back independently of the writer's caller: same tissues, conforming, positive tets.
  const TetMesh tg = read_vtu((dir / "out/mesh_tetgen.vtu").string());
  EXPECT_EQ(tg.tissue_names, test::block_mesh().tissue_names);
  const auto record = nlohmann::json::parse(read_file(dir / "out/check.json"));
  EXPECT_EQ(record["conformity"]["tetgen"]["faces_shared_by_more_than_two"], 0);
  EXPECT_EQ(record["conformity"]["tetgen"]["inverted_tets"], 0);
  // TetGen keeps the input triangles (-Y), so the tissues enclose exactly the block's volumes
  // and every interface keeps its area.
  const double volumes[] = {800.0, 600.0, 600.0};
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(record["tissues"][i]["tetgen"]["volume_mm3"].get<double>(), volumes[i],
                test::kRelativeRoundoff * volumes[i]);
  }
  // The radius-edge figures (TetGen's -q bound is 2 by default) are those of the mesh written.
  const QualityReport tg_quality = compute_quality(tg);
  const auto& total = record["tissues"][3];
  ASSERT_EQ(total["tissue"], "all tissues");
  EXPECT_EQ(total["tetgen"]["max_radius_edge_ratio"].get<double>(), tg_quality.total.max_radius_edge_ratio);
  EXPECT_EQ(total["tetgen"]["tets_radius_edge_above_2"].get<std::size_t>(),
            tg_quality.total.tets_radius_edge_above_2);
  std::cout << "[ check    ] block: TetGen max radius-edge ratio " << tg_quality.total.max_radius_edge_ratio << ", "
            << tg_quality.total.tets_radius_edge_above_2 << " tets above 2\n";
  // The configured bound (default 2) and the ratio the input forces: the block's faces are right
  // isosceles triangles (1 / (2 sin 45 deg) = 1/sqrt 2), and no mesh keeping them goes below it.
  const auto& tetgen = record["tetgen"];
  EXPECT_EQ(tetgen["radius_edge_ratio_bound"].get<double>(), 2.0);
  // The default sizing: TetGen gets the block mesh's edge lengths at the surface nodes (-m).
  EXPECT_NE(tetgen["switches"].get<std::string>().find('m'), std::string::npos);
  EXPECT_NE(tetgen["sizing"].get<std::string>().find("sizes from MESH"), std::string::npos);
  EXPECT_EQ(tetgen["tets_above_radius_edge_bound"].get<std::size_t>(), tg_quality.total.tets_radius_edge_above_2);
  EXPECT_EQ(tetgen["mesh_tets_above_radius_edge_bound"].get<std::size_t>(), total["mesh"]["tets_radius_edge_above_2"].get<std::size_t>());
  const auto& forced = tetgen["radius_edge_ratio_forced_by_input"];
  EXPECT_NEAR(forced["ratio"].get<double>(), 1.0 / std::sqrt(2.0), test::kRelativeRoundoff);
  EXPECT_NEAR(forced["triangle"]["min_angle_deg"].get<double>(), 45.0, test::kAngleDeg);
  EXPECT_EQ(forced["input_triangles_above_bound"].get<std::size_t>(), 0u);
  EXPECT_EQ(forced["triangle"]["vertices_mm"].size(), 3u);
  EXPECT_GE(tg_quality.total.max_radius_edge_ratio, forced["ratio"].get<double>() * (1.0 - test::kRelativeRoundoff));
  EXPECT_NE(r.out.find("forced by the input ("), std::string::npos) << r.out;
  // The account of the tets above the bound: no input triangle forces more than 2 here, so every
  // such tet, in either mesh, is counted as not forced.
  for (const char* side : {"tetgen", "mesh"}) {
    const auto& a = tetgen["tets_above_radius_edge_bound_account"][side];
    const std::size_t above = tetgen[std::string(side) == "tetgen" ? "tets_above_radius_edge_bound"
                                                                     : "mesh_tets_above_radius_edge_bound"]
                                  .get<std::size_t>();
    EXPECT_EQ(a["above"].get<std::size_t>(), above) << side;
    EXPECT_EQ(a["forced_by_input_triangle"].get<std::size_t>(), 0u) << side;
    EXPECT_EQ(a["not_forced"].get<std::size_t>(), above) << side;
    std::size_t by_nodes = 0;
    ASSERT_EQ(a["not_forced_by_surface_nodes"].size(), 5u) << side;
    for (const auto& n : a["not_forced_by_surface_nodes"]) by_nodes += n.get<std::size_t>();
    EXPECT_EQ(by_nodes, above) << side;
    EXPECT_TRUE(a["max_ratio_not_forced"].is_number()) << side;
  }
  EXPECT_NE(r.out.find("not forced by the input"), std::string::npos) << r.out;
  for (const auto& f : record["interfaces"])
    EXPECT_NEAR(f["tetgen_area_mm2"].get<double>(), f["mesh_area_mm2"].get<double>(),
                test::kRelativeRoundoff * f["mesh_area_mm2"].get<double>())
        << f["interface"];
  // The cross-mesh bound: the tumor's mean displacement under gravity within 5 % between the meshes
  // (docs/verification.md, "Cross-check with TetGen").
  const double d = record["target"]["difference_percent"];
  std::cout << "[ check    ] block: tumor mean displacement differs by " << d << " % between the meshes\n";
  EXPECT_LE(d, 100.0 * test::kCrossMeshDisplacementRel);
  EXPECT_GT(d, 0.0);  // two different meshes: a zero difference would mean one solve was reused
  EXPECT_NE(r.out.find("TetGen cross-check"), std::string::npos);
}

TEST_F(Check, GmshComputesTheSameGammaAndSicnAsWeDoOnEveryTet) {
  // The block's tets are all alike; jitter its nodes so that shapes spread from regular-ish to
  // flat, and some tets invert (SICN's sign must agree too). Deterministic: mt19937's raw output.
  TetMesh mesh = test::block_mesh();
  std::mt19937 random(7);
  for (auto& p : mesh.points)
    for (int c = 0; c < 3; ++c) p[c] += 1.2 * (static_cast<double>(random()) / std::mt19937::max() - 0.5);
  write_vtu(mesh, (dir / "jittered.vtu").string());
  const auto r = run_cli("check jittered.vtu -c block.yaml -o out --gmsh", dir);
  std::cout << r.out;
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const std::string& f : files_below(dir / "out"))
    EXPECT_TRUE(f == "check.json" || f == "report.html" || f == "quality_gmsh.pos") << "unexpected output " << f;
  const auto record = nlohmann::json::parse(read_file(dir / "out/check.json"));
  EXPECT_TRUE(record["agree"].get<bool>());
  EXPECT_LE(record["max_gamma_difference"].get<double>(), test::kGmshPrintedQualityAbs);
  EXPECT_LE(record["max_sicn_difference"].get<double>(), test::kGmshPrintedQualityAbs);
  // The comparison covered a real spread of shapes, inverted ones included.
  const auto& all = record["tissues"].back();
  ASSERT_EQ(all["tissue"], "all tissues");
  EXPECT_EQ(all["tets"], mesh.tets.size());
  EXPECT_LT(all["gamma"]["min_gmsh"].get<double>(), 0.3);
  EXPECT_GT(all["gamma"]["mean_gmsh"].get<double>(), 0.5);
  EXPECT_LT(all["sicn"]["min_gmsh"].get<double>(), 0.0);
  EXPECT_NEAR(all["sicn"]["min_ours"].get<double>(), all["sicn"]["min_gmsh"].get<double>(), test::kGmshPrintedQualityAbs);
  EXPECT_EQ(record["gmsh"]["version"].get<std::string>().rfind("4.8", 0), 0u) << record["gmsh"]["version"];
  // One Gmsh record per tet in the statistics view the user can open in Gmsh.
  const std::string pos = read_file(dir / "out/quality_gmsh.pos");
  std::size_t records = 0;
  for (std::size_t at = pos.find("\nSS("); at != std::string::npos; at = pos.find("\nSS(", at + 1)) ++records;
  EXPECT_EQ(records, mesh.tets.size());
}

TEST_F(Check, TetgenSizedByVolumeBoundsWhenAsked) {
  // tetgen.size_from_mesh: false gives TetGen the per-tissue volume bounds of the regular tet of
  // each tissue's mean boundary edge instead of the block mesh's sizes: no -m, and a different mesh.
  std::ofstream(dir / "bounds.yaml") << read_file(dir / "block.yaml") << "tetgen: {size_from_mesh: false}\n";
  const auto bounds = run_cli("check block.vtu -c bounds.yaml -o by_bounds --tetgen", dir);
  ASSERT_EQ(bounds.exit_code, 0) << bounds.err;
  const auto sized = run_cli("check block.vtu -c block.yaml -o by_mesh --tetgen", dir);
  ASSERT_EQ(sized.exit_code, 0) << sized.err;
  const auto a = nlohmann::json::parse(read_file(dir / "by_bounds/check.json"));
  const auto b = nlohmann::json::parse(read_file(dir / "by_mesh/check.json"));
  EXPECT_EQ(a["tetgen"]["switches"], "pzQAaYq2/0");
  EXPECT_EQ(a["tetgen"]["sizing"], "per-tissue volume bounds");
  EXPECT_EQ(b["tetgen"]["switches"], "pzQAamYq2/0");
  EXPECT_NE(a["tissues"][3]["tetgen"]["tets"], b["tissues"][3]["tetgen"]["tets"]);
}

TEST_F(Check, TetgenWithAnUnknownTargetIsBadInput) {
  const auto r = run_cli("check block.vtu -c block.yaml -o out --tetgen --target liver", dir);
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("'liver' is not a tissue"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "out"));
}

}  // namespace
