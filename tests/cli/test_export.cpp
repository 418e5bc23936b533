// `tissuemesh export` and the demo's model files, through the program: CalculiX solves the deck
// the demo writes (tet4 and tet10), every format lands, the output is deterministic, and bad
// material input is refused with exit code 2 and nothing written.
#include "cli/cli_runner.h"
#include "core/model_builder.h"
#include "core/vtu_io.h"
#include "materials/material_config.h"
#include "solver_check/calculix_dat.h"
#include "solver_check/calculix_run.h"
#include "support/model_fixture.h"
#include "support/support_load.h"
#include "support/test_paths.h"
#include "support/tolerances.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <fstream>

using namespace tissuemesh;
using test::files_below;
using test::read_file;
using test::run_cli;

namespace {

// The model the program built, rebuilt through the library from the same mesh and config.
Model model_of(const std::filesystem::path& mesh, const std::string& config) {
  YamlMap top(load_yaml_file(config), "", config);
  YamlMap materials = top.map("materials");
  const MaterialTable table = MaterialTable::from_yaml(materials, config);
  YamlMap model = top.map("model");
  return build_model(read_vtu(mesh.string()), ModelSettings::from_yaml(model), table.tissues, config);
}

// ccx on <dir>/model.inp; checks what the acceptance asks: it runs to the end, the breast moves
// with gravity, the fixed chest wall holds the whole weight.
void solve_and_check(const std::filesystem::path& dir, const Model& model) {
  if (find_calculix().empty()) GTEST_SKIP() << "ccx not found";
  const CalculixRun run = run_calculix((dir / "model.inp").string(), 2);
  std::cout << "[ ccx      ] " << model.elements.size() << (model.order == ElementOrder::Linear ? " tet4" : " tet10")
            << ", " << model.nodes.size() << " nodes: " << run.seconds << " s\n";
  ASSERT_EQ(run.exit_code, 0) << run.log;
  EXPECT_EQ(run.log.find("*ERROR"), std::string::npos);
  const std::vector<DatBlock> blocks = read_calculix_dat(run.dat_path);
  const DatBlock& u = last_block(blocks, "displacements", "NALL");
  EXPECT_EQ(u.time, 1.0) << "the step ran to its end";
  ASSERT_EQ(u.values.size(), model.nodes.size());

  // Prone gravity points to -y (anterior): the free breast tissue moves that way on average and
  // its largest sag is anterior; the chest wall does not move.
  const NodeSet& wall = model.node_sets.at(0);
  std::set<int> fixed(wall.nodes.begin(), wall.nodes.end());
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  double max_norm = 0.0, min_uy = 0.0;
  for (const auto& [id, d] : u.values) {
    if (fixed.count(id - 1)) {
      EXPECT_EQ(d, Eigen::Vector3d::Zero()) << "fixed node " << id;
      continue;
    }
    mean += d;
    max_norm = std::max(max_norm, d.norm());
    min_uy = std::min(min_uy, d.y());
  }
  mean /= static_cast<double>(u.values.size() - fixed.size());
  std::cout << "[ ccx      ] max |u| " << max_norm << " mm, mean u (" << mean.transpose() << ") mm\n";
  EXPECT_LT(mean.y(), 0.0);
  EXPECT_GT(std::abs(mean.y()), 3.0 * std::max(std::abs(mean.x()), std::abs(mean.z())));
  EXPECT_NEAR(min_uy, -max_norm, 0.1 * max_norm) << "the largest displacement is along gravity";

  // Sum of reactions = total weight (RF misses the load lumped on the fixed nodes: added back).
  const DatBlock& rf = last_block(blocks, "forces", "CHEST_WALL");
  ASSERT_TRUE(rf.has_total);
  const test::SupportLoad w = test::support_load(model, wall.nodes);
  const Eigen::Vector3d reaction = rf.total - w.on_set;
  std::cout << "[ ccx      ] weight " << w.total.norm() << " N, reaction (" << reaction.transpose() << ") N\n";
  EXPECT_NEAR((reaction + w.total).norm(), 0.0, test::kCalculixEquilibriumRel * w.total.norm());
}

}  // namespace

TEST(Export, CoarseDemoTet4RunsInCalculix) {
  const auto dir = test::scratch_dir();
  const auto r = run_cli("demo -c " + test::config_path("phantom-coarse.yaml") + " --out demo", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* f : {"model.feb", "model.inp", "model.scn", "model.vtk", "model.vtu", "model.msh", "export.json"})
    EXPECT_TRUE(std::filesystem::exists(dir / "demo" / f)) << f;
  const auto record = nlohmann::json::parse(read_file(dir / "demo/export.json"));
  EXPECT_EQ(record["model"]["element"], "tet4");
  const Model model = model_of(dir / "demo/mesh.vtu", test::config_path("phantom-coarse.yaml"));
  EXPECT_NEAR(record["model"]["total_weight_N"].get<double>(), test::support_load(model, {}).total.norm(),
              1e-9 * record["model"]["total_weight_N"].get<double>());
  solve_and_check(dir / "demo", model);
}

TEST(Export, CoarseDemoTet10RunsInCalculix) {
  const auto dir = test::scratch_dir();
  const std::string coarse = test::config_path("phantom-coarse.yaml");
  ASSERT_EQ(run_cli("demo -c " + coarse + " --out demo --skip-calculix", dir).exit_code, 0);
  const std::string config = test::coarse_config(dir, "tet10");
  const auto r = run_cli("export demo/mesh.vtu -c " + config + " -o tet10 --format abaqus", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(files_below(dir / "tet10"), (std::vector<std::string>{"export.json", "model.inp"}));
  const Model model = model_of(dir / "demo/mesh.vtu", config);
  ASSERT_EQ(model.order, ElementOrder::Quadratic);
  solve_and_check(dir / "tet10", model);
}

TEST(Export, WritesEachFormatDeterministically) {
  const auto dir = test::scratch_dir();
  write_vtu(test::block_mesh(), (dir / "block.vtu").string());
  std::ofstream(dir / "block.yaml") << R"(materials:
  fat: {law: neo-hookean, mu: 150 Pa, K: 50 kPa, density: 1000 kg/m^3}
  fgt: {law: mooney-rivlin, C10: 100 Pa, C01: 50 Pa, K: 60 kPa, density: 1040 kg/m^3}
  tumor: {law: neo-hookean, E: 9.6 kPa, nu: 0.49, density: 1060 kg/m^3}
model:
  node_sets: [{name: wall, plane: {point_mm: [0, 10, 0], normal: [0, 1, 0], tolerance_mm: 0.01}}]
)";
  ASSERT_EQ(run_cli("export block.vtu -c block.yaml -o a", dir).exit_code, 0);
  ASSERT_EQ(run_cli("export block.vtu -c block.yaml -o b", dir).exit_code, 0);
  EXPECT_EQ(files_below(dir / "a"), (std::vector<std::string>{"export.json", "model.feb", "model.inp", "model.msh",
                                                             "model.scn", "model.vtk", "model.vtu"}));
  for (const char* f : {"model.feb", "model.inp", "model.msh", "model.scn", "model.vtk", "model.vtu"})
    EXPECT_EQ(read_file(dir / "a" / f), read_file(dir / "b" / f)) << f;
  const auto only = run_cli("export block.vtu -c block.yaml -o c --format febio,sofa", dir);
  ASSERT_EQ(only.exit_code, 0) << only.err;
  EXPECT_EQ(files_below(dir / "c"), (std::vector<std::string>{"export.json", "model.feb", "model.scn", "model.vtk"}));
  EXPECT_NE(only.out.find("total weight"), std::string::npos);
}

TEST(Export, PrintedConfigsAreTheDefaultsAndEveryShippedConfigLoads) {
  const auto dir = test::scratch_dir();
  const auto builtin = run_cli("demo --print-config", dir);
  const auto file = run_cli("demo -c " + test::config_path("phantom.yaml") + " --print-config", dir);
  ASSERT_EQ(builtin.exit_code, 0) << builtin.err;
  EXPECT_EQ(builtin.out, file.out) << "configs/phantom.yaml documents the built-in defaults";
  for (const char* name : {"phantom-coarse.yaml", "breast-generic.yaml"}) {
    const auto r = run_cli(std::string("demo -c ") + test::config_path(name) + " --print-config", dir);
    EXPECT_EQ(r.exit_code, 0) << name << ": " << r.err;
    // The printed effective config loads again and prints the same.
    std::ofstream(dir / "effective.yaml") << r.out;
    EXPECT_EQ(run_cli("demo -c effective.yaml --print-config", dir).out, r.out) << name;
  }
}

class BadMaterial : public ::testing::Test {
 protected:
  void SetUp() override {
    dir = test::scratch_dir();
    write_vtu(test::block_mesh(), (dir / "block.vtu").string());
  }
  // `fat` is the entry under test; fgt and tumor are valid.
  void expect_refused(const std::string& fat, const std::vector<std::string>& needles) {
    std::ofstream(dir / "bad.yaml") << "materials:\n"
                                    << (fat.empty() ? "" : "  fat: " + fat + "\n")
                                    << "  fgt: {law: neo-hookean, mu: 300 Pa, K: 50 kPa, density: 1000 kg/m^3}\n"
                                       "  tumor: {law: neo-hookean, mu: 900 Pa, K: 50 kPa, density: 1000 kg/m^3}\n"
                                       "model: {node_sets: [{name: wall, box_mm: [0, 9, 0, 20, 11, 10]}]}\n";
    const auto r = run_cli("export block.vtu -c bad.yaml -o out", dir);
    EXPECT_EQ(r.exit_code, 2) << fat << "\n" << r.err;
    for (const std::string& n : needles) EXPECT_NE(r.err.find(n), std::string::npos) << "missing '" << n << "' in: " << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir / "out")) << "nothing written";
  }
  std::filesystem::path dir;
};

TEST_F(BadMaterial, PoissonRatioOfOneHalf) {
  expect_refused("{law: neo-hookean, E: 3 kPa, nu: 0.5, density: 1000 kg/m^3}",
                 {"bad.yaml: materials.fat", "nu = 0.5", "bulk modulus"});
}
TEST_F(BadMaterial, NonPositiveShearModulus) {
  expect_refused("{law: neo-hookean, mu: 0 Pa, K: 50 kPa, density: 1000 kg/m^3}", {"materials.fat", "shear modulus"});
  expect_refused("{law: neo-hookean, mu: -5 Pa, K: 50 kPa, density: 1000 kg/m^3}", {"materials.fat", "positive"});
}
TEST_F(BadMaterial, TissueWithoutMaterial) { expect_refused("", {"tissue 'fat'", "has no material"}); }
TEST_F(BadMaterial, UnknownLaw) {
  expect_refused("{law: yeoh, mu: 150 Pa, K: 50 kPa, density: 1000 kg/m^3}", {"materials.fat.law", "unknown law 'yeoh'"});
}
TEST_F(BadMaterial, UnknownKey) {
  expect_refused("{law: neo-hookean, mu: 150 Pa, K: 50 kPa, density: 1000 kg/m^3, colour: red}",
                 {"materials.fat", "colour"});
}
TEST_F(BadMaterial, InconsistentUnits) {
  expect_refused("{law: neo-hookean, mu: 150, K: 50 kPa, density: 1000 kg/m^3}", {"materials.fat.mu", "no unit"});
  expect_refused("{law: neo-hookean, mu: 150 kg/m^3, K: 50 kPa, density: 1000 kg/m^3}",
                 {"materials.fat.mu", "wrong kind of unit"});
  expect_refused("{law: neo-hookean, mu: 150 Pa, K: 50 kPa, density: 1e-9 kg/m^3}",
                 {"materials.fat.density", "not a tissue density"});
}
TEST_F(BadMaterial, NoExactCalculixEquivalent) {
  expect_refused("{law: compressible-neo-hookean, mu: 150 Pa, K: 50 kPa, density: 1000 kg/m^3}",
                 {"tissue 'fat'", "no exact Abaqus/CalculiX equivalent"});
}
