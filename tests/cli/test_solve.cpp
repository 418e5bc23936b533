// `tissuemesh solve` through the program, on the block of tests/support/model_fixture.h hanging
// from its posterior face: what lands in the folder, solution.vtu read back by VTK in the node
// order of the exported model.vtu, equilibrium in solve.json, determinism, the same answer in every
// unit system, and the failure modes (refused model: exit 2, nothing written; no convergence:
// exit 1 with both files of the last accepted state, never a NaN).
#include "cli/cli_runner.h"
#include "core/vtu_io.h"
#include "support/model_fixture.h"
#include "support/test_paths.h"
#include "support/tolerances.h"

#include <gtest/gtest.h>
#include <regex>
#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkFieldData.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkSmartPointer.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLUnstructuredGridReader.h>

#include <nlohmann/json.hpp>

#include <cmath>
#include <fstream>
#include <regex>

using namespace tissuemesh;
using test::files_below;
using test::expect_no_nan_text;
using test::read_file;
using test::run_cli;

namespace {

const char* const kMaterials = R"(materials:
  fat: {law: neo-hookean, mu: 150 Pa, K: 50 kPa, density: 1000 kg/m^3}
  fgt: {law: mooney-rivlin, C10: 100 Pa, C01: 50 Pa, K: 60 kPa, density: 1040 kg/m^3}
  tumor: {law: neo-hookean, E: 9.6 kPa, nu: 0.49, density: 1060 kg/m^3}
)";
// The posterior face y = 10 mm is the chest wall; prone gravity pulls towards y = 0.
const char* const kWall = "  node_sets: [{name: wall, plane: {point_mm: [0, 10, 0], normal: [0, 1, 0], tolerance_mm: 0.01}}]\n";

class Solve : public ::testing::Test {
 protected:
  void SetUp() override {
    dir = test::scratch_dir();
    write_vtu(test::block_mesh(), (dir / "block.vtu").string());
  }
  /// Writes <name>.yaml: the materials (or `materials`) and a `model:` section of `model_keys`
  /// (each line indented by two spaces) after the wall. The default asks for tet4 explicitly: these
  /// tissues have nu >= 0.49, so `element: auto` would choose tet10.
  std::string config(const std::string& name, const std::string& model_keys = "  element: tet4\n",
                     const std::string& materials = kMaterials) {
    std::ofstream(dir / (name + ".yaml")) << materials << "model:\n" << kWall << model_keys;
    return name + ".yaml";
  }
  std::filesystem::path dir;
};

vtkSmartPointer<vtkUnstructuredGrid> read_grid(const std::filesystem::path& path) {
  vtkNew<vtkXMLUnstructuredGridReader> reader;
  reader->SetFileName(path.string().c_str());
  reader->Update();
  vtkSmartPointer<vtkUnstructuredGrid> grid = reader->GetOutput();
  return grid;
}

std::string string_field(vtkUnstructuredGrid* grid, const char* name) {
  // A text field: one Int32 tuple whose component name is the value (meshio reads no String arrays).
  vtkDataArray* a = grid->GetFieldData()->GetArray(name);
  return a && a->GetNumberOfTuples() == 1 && a->GetNumberOfComponents() == 1 && a->GetComponentName(0)
             ? a->GetComponentName(0) : "<missing>";
}

/// Every value of every point, cell and field data array and every coordinate is finite.
void expect_all_finite(vtkUnstructuredGrid* grid) {
  for (vtkFieldData* data : {static_cast<vtkFieldData*>(grid->GetPointData()),
                             static_cast<vtkFieldData*>(grid->GetCellData()), grid->GetFieldData()})
    for (int i = 0; i < data->GetNumberOfArrays(); ++i) {
      vtkDataArray* a = data->GetArray(i);
      if (a == nullptr) continue;  // string arrays
      for (vtkIdType t = 0; t < a->GetNumberOfTuples(); ++t)
        for (int c = 0; c < a->GetNumberOfComponents(); ++c)
          ASSERT_TRUE(std::isfinite(a->GetComponent(t, c))) << a->GetName() << " tuple " << t;
    }
  for (vtkIdType i = 0; i < grid->GetNumberOfPoints(); ++i) {
    double p[3];
    grid->GetPoint(i, p);
    ASSERT_TRUE(std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2])) << i;
  }
}

std::vector<Eigen::Vector3d> points(vtkUnstructuredGrid* grid) {
  std::vector<Eigen::Vector3d> p(static_cast<std::size_t>(grid->GetNumberOfPoints()));
  for (vtkIdType i = 0; i < grid->GetNumberOfPoints(); ++i) grid->GetPoint(i, p[i].data());
  return p;
}

}  // namespace

TEST_F(Solve, ATerminalSeesALiveProgressBar) {
  // bsdutils' script(1) runs the command on a pseudo-terminal, as a user's shell would.
  if (std::system("command -v script > /dev/null 2>&1") != 0) GTEST_SKIP() << "script(1) not installed";
  const std::string cfg = config("block");
  const std::string cmd = "cd '" + dir.string() + "' && TERM=xterm script -qec '" + std::string(TISSUEMESH_EXE) +
                          " solve block.vtu -c " + cfg + " -o out --no-html' /dev/null > tty.txt 2>&1";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << read_file(dir / "tty.txt");
  const std::string out = read_file(dir / "tty.txt");
  EXPECT_NE(out.find("\r  [########################] 100%"), std::string::npos) << out;  // the last increment
  // No plain note line ("    0.20 s  increment 1: ...") for the increments: the bar replaces them.
  EXPECT_FALSE(std::regex_search(out, std::regex("\n +[0-9.]+ s  increment 1: load"))) << out;
  EXPECT_NE(out.find("solve (built-in, tet4"), std::string::npos) << out;
}

TEST_F(Solve, WritesSolutionInTheModelNodeOrderAndABalancedRecord) {
  const std::string cfg = config("block");
  const auto r = run_cli("solve block.vtu -c " + cfg + " -o out", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err << r.out;
  EXPECT_EQ(files_below(dir / "out"), (std::vector<std::string>{"report.html", "solution.vtu", "solve.json"}));
  EXPECT_NE(r.out.find("> solve (built-in, tet4, "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("increment 1: load "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("wrote "), std::string::npos) << r.out;

  // solution.vtu has model.vtu's points, in model.vtu's order, and the same cells.
  ASSERT_EQ(run_cli("export block.vtu -c " + cfg + " -o exported --format vtu", dir).exit_code, 0);
  const auto model_vtu = read_grid(dir / "exported/model.vtu");
  const auto grid = read_grid(dir / "out/solution.vtu");
  ASSERT_GT(grid->GetNumberOfPoints(), 0);
  EXPECT_EQ(points(grid), points(model_vtu)) << "identical coordinates in identical order";
  ASSERT_EQ(grid->GetNumberOfCells(), model_vtu->GetNumberOfCells());
  for (vtkIdType c = 0; c < grid->GetNumberOfCells(); ++c) {
    vtkIdType n = 0, m = 0;
    const vtkIdType *a = nullptr, *b = nullptr;
    grid->GetCellPoints(c, n, a);
    model_vtu->GetCellPoints(c, m, b);
    ASSERT_EQ(std::vector<vtkIdType>(a, a + n), std::vector<vtkIdType>(b, b + m)) << c;
  }
  vtkDataArray* u = grid->GetPointData()->GetArray("displacement");
  ASSERT_NE(u, nullptr);
  EXPECT_EQ(u->GetNumberOfComponents(), 3);
  EXPECT_EQ(u->GetNumberOfTuples(), grid->GetNumberOfPoints());
  vtkDataArray* wall = grid->GetPointData()->GetArray("set_wall");
  ASSERT_NE(wall, nullptr);
  for (const auto& [name, comps] : std::vector<std::pair<std::string, int>>{
           {"cauchy_stress", 6}, {"von_mises_stress", 1}, {"J", 1}, {"tissue_id", 1}, {"shear_modulus_Pa", 1}}) {
    vtkDataArray* a = grid->GetCellData()->GetArray(name.c_str());
    ASSERT_NE(a, nullptr) << name;
    EXPECT_EQ(a->GetNumberOfComponents(), comps) << name;
    EXPECT_EQ(a->GetNumberOfTuples(), grid->GetNumberOfCells()) << name;
  }
  expect_all_finite(grid);
  EXPECT_EQ(string_field(grid, "displacement_unit"), "mm");
  EXPECT_EQ(string_field(grid, "stress_unit"), "Pa");
  EXPECT_EQ(string_field(grid, "solver_converged"), "true");
  EXPECT_EQ(grid->GetFieldData()->GetArray("load_fraction")->GetTuple1(0), 1.0);

  const std::string text = read_file(dir / "out/solve.json");
  expect_no_nan_text(text);
  const auto j = nlohmann::json::parse(text);
  EXPECT_TRUE(j["solver"]["converged"].get<bool>()) << j["solver"]["message"];
  EXPECT_EQ(j["solver"]["load_fraction"], 1.0);
  ASSERT_FALSE(j["solver"]["steps"].empty());
  for (const auto& s : j["solver"]["steps"]) {
    EXPECT_FALSE(s["residual_norms"].empty());
    for (const char* key : {"load_fraction", "increment", "iterations", "step_lengths", "accepted", "note", "seconds"})
      EXPECT_TRUE(s.contains(key)) << key;
  }
  const auto& res = j["results"];
  // The sum of all nodal forces is the sum of the free residuals, at most sqrt(n) times their
  // norm: see kSolverDefaultEquilibriumRel.
  EXPECT_LE(res["reaction_vs_weight_rel"].get<double>(), test::kSolverDefaultEquilibriumRel);
  const Eigen::Vector3d weight(res["total_weight_N"][0], res["total_weight_N"][1], res["total_weight_N"][2]);
  EXPECT_NEAR(weight.norm(), j["model"]["total_weight_N"].get<double>(),
              test::kRelativeRoundoff * weight.norm());
  EXPECT_LT(weight.y(), 0.0) << "prone: towards anterior, -y";
  ASSERT_EQ(res["tissues"].size(), 3u);
  EXPECT_EQ(res["tissues"][2]["name"], "tumor");
  for (const auto& t : res["tissues"]) EXPECT_LT(t["centroid_displacement_mm"][1].get<double>(), 0.0) << t["name"];
  for (const char* key : {"peak_memory_mib", "versions", "timings", "inputs", "config", "model", "units"})
    EXPECT_TRUE(j.contains(key)) << key;

  // The record's largest displacement is the file's, at the node it names (1-based), in mm.
  double max_u = 0.0;
  vtkIdType at = -1;
  for (vtkIdType i = 0; i < u->GetNumberOfTuples(); ++i) {
    const double* d = u->GetTuple3(i);
    const double norm = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    if (wall->GetTuple1(i) == 1.0) {
      EXPECT_EQ(norm, 0.0) << "fixed node " << i;
    }
    if (norm > max_u) {
      max_u = norm;
      at = i;
    }
  }
  EXPECT_GT(max_u, 0.1) << "the block sags by a visible amount";
  EXPECT_NEAR(res["max_displacement_mm"].get<double>(), max_u, test::kRelativeRoundoff * max_u);
  EXPECT_EQ(res["max_displacement_node"].get<vtkIdType>(), at + 1);
}

TEST_F(Solve, SolutionIsByteIdenticalAcrossRunsAndThreadCounts) {
  const std::string cfg = config("block");
  ASSERT_EQ(run_cli("solve block.vtu -c " + cfg + " -o a", dir).exit_code, 0);
  ASSERT_EQ(run_cli("solve block.vtu -c " + cfg + " -o b", dir).exit_code, 0);
  ASSERT_EQ(run_cli("solve block.vtu -c " + cfg + " -o c --threads 1", dir).exit_code, 0);
  const std::string a = read_file(dir / "a/solution.vtu");
  EXPECT_FALSE(a.empty());
  EXPECT_EQ(a, read_file(dir / "b/solution.vtu"));
  EXPECT_EQ(a, read_file(dir / "c/solution.vtu")) << "one thread and the default give the same bits";
}

TEST_F(Solve, Tet10SolutionKeepsTheModelOrderAndEveryUnitSystemGivesTheSameMillimetres) {
  const std::string tet10 = config("tet10", "  element: tet10\n");
  const auto r = run_cli("solve block.vtu -c " + tet10 + " -o q", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  ASSERT_EQ(run_cli("export block.vtu -c " + tet10 + " -o qe --format vtu", dir).exit_code, 0);
  const auto grid = read_grid(dir / "q/solution.vtu");
  EXPECT_EQ(points(grid), points(read_grid(dir / "qe/model.vtu")));
  EXPECT_EQ(grid->GetPointData()->GetArray("displacement")->GetNumberOfTuples(), grid->GetNumberOfPoints());
  expect_all_finite(grid);

  // The same tet4 model solved in mm-t-s, SI (metres, Pa) and mm-kg-s (mN): reported in mm and N.
  std::vector<nlohmann::json> results;
  for (const char* units : {"mm-t-s", "SI", "mm-kg-s"}) {
    const std::string cfg = config(std::string("units-") + units, std::string("  element: tet4\n  units: ") + units + "\n");
    const auto run = run_cli("solve block.vtu -c " + cfg + " -o " + units, dir);
    ASSERT_EQ(run.exit_code, 0) << units << ": " << run.err;
    results.push_back(nlohmann::json::parse(read_file(dir / units / "solve.json"))["results"]);
  }
  const double u0 = results[0]["max_displacement_mm"].get<double>();
  for (const auto& res : results) {
    EXPECT_NEAR(res["max_displacement_mm"].get<double>(), u0, test::kUnitSystemSolveRel * u0);
    EXPECT_EQ(res["max_displacement_node"], results[0]["max_displacement_node"]);
    for (int k = 0; k < 3; ++k) {
      const double w0 = results[0]["total_weight_N"][k].get<double>();
      EXPECT_NEAR(res["total_weight_N"][k].get<double>(), w0, test::kRelativeRoundoff * std::abs(w0) + 1e-300);
      const double t0 = results[0]["tissues"][2]["centroid_displacement_mm"][k].get<double>();
      EXPECT_NEAR(res["tissues"][2]["centroid_displacement_mm"][k].get<double>(), t0, test::kUnitSystemSolveRel * u0);
    }
  }
}

TEST_F(Solve, ZeroDensityTissueIsRefusedAndNothingIsWritten) {
  std::string materials = kMaterials;
  materials = std::regex_replace(materials, std::regex("density: 1040 kg/m\\^3"), "density: 0 kg/m^3");
  const auto r = run_cli("solve block.vtu -c " + config("zero", "", materials) + " -o out", dir);
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("fgt"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("density"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "out"));
}

TEST_F(Solve, ModelWithoutFixedSetIsRefusedAndNothingIsWritten) {
  std::ofstream(dir / "free.yaml") << kMaterials << "model: {node_sets: []}\n";
  const auto r = run_cli("solve block.vtu -c free.yaml -o out", dir);
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("tissuemesh solve: error: "), std::string::npos) << r.err;
  EXPECT_TRUE(std::regex_search(r.err, std::regex("fixed|constrain", std::regex::icase))) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "out"));
}

TEST_F(Solve, NonConvergenceWritesTheLastAcceptedStateAndExitsOne) {
  // One Newton iteration can never converge (the displacement criterion compares the correction
  // with the displacement, which it is), and no increment below half the load is allowed.
  const std::string soft = std::regex_replace(std::string(kMaterials), std::regex("mu: 150 Pa"), "mu: 1 Pa");
  const std::string cfg = config("stuck",
                                 "  element: tet4\n"
                                 "  gravity: {direction: prone, acceleration: 100 m/s^2}\n"
                                 "  analysis: {load_steps: 1, max_newton_iterations: 1, min_step_fraction: 0.5}\n",
                                 soft);
  const auto r = run_cli("solve block.vtu -c " + cfg + " -o out", dir);
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(r.err.find("tissuemesh solve: error: did not converge: "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("load fraction 0 reached; see "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("solve.json"), std::string::npos) << r.err;
  EXPECT_EQ(files_below(dir / "out"), (std::vector<std::string>{"report.html", "solution.vtu", "solve.json"}));

  const std::string text = read_file(dir / "out/solve.json");
  expect_no_nan_text(text);
  const auto j = nlohmann::json::parse(text);
  EXPECT_FALSE(j["solver"]["converged"].get<bool>());
  EXPECT_FALSE(j["solver"]["message"].get<std::string>().empty());
  EXPECT_EQ(j["solver"]["load_fraction"], 0.0);
  ASSERT_FALSE(j["solver"]["steps"].empty());
  for (const auto& s : j["solver"]["steps"]) EXPECT_FALSE(s["accepted"].get<bool>());
  EXPECT_TRUE(j["results"]["reaction_vs_weight_rel"].is_number());

  const auto grid = read_grid(dir / "out/solution.vtu");
  ASSERT_EQ(grid->GetPointData()->GetArray("displacement")->GetNumberOfTuples(), grid->GetNumberOfPoints());
  expect_all_finite(grid);
  EXPECT_EQ(string_field(grid, "solver_converged"), "false");
  EXPECT_EQ(grid->GetFieldData()->GetArray("load_fraction")->GetTuple1(0), 0.0);
}

TEST_F(Solve, HelpStatesUnitsAndBadOptionsExitTwo) {
  const auto help = run_cli("solve --help", dir);
  EXPECT_EQ(help.exit_code, 0);
  for (const char* s : {"solution.vtu", "solve.json", "mm", "Pa", "--threads", "--print-config"})
    EXPECT_NE(help.out.find(s), std::string::npos) << s;
  EXPECT_EQ(run_cli("solve block.vtu -c " + config("block") + " -o out --threads -3", dir).exit_code, 2);
  EXPECT_EQ(run_cli("solve missing.vtu -c " + config("block") + " -o out", dir).exit_code, 2);
  EXPECT_FALSE(std::filesystem::exists(dir / "out"));
  const auto printed = run_cli("solve block.vtu -c " + config("block") + " --print-config", dir);
  EXPECT_EQ(printed.exit_code, 0);
  EXPECT_NE(printed.out.find("residual_tolerance"), std::string::npos);
}
