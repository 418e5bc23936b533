// `tissuemesh sweep` on the coarse phantom: every sample of a 3 x 3 grid equals a separate
// `tissuemesh solve` with that sample's config (with and without warm starts, one and two jobs);
// a sweep killed with SIGKILL and rerun ends with the uninterrupted run's results.csv; shards
// merged give the local table; a Sobol' design reports indices; bad sweep files are refused by name
// and a sample that makes no physical material is a failed row, not a stopped sweep.
#include "cli/cli_runner.h"
#include "support/test_paths.h"

#include <gtest/gtest.h>
#include <vtkDataArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLUnstructuredGridReader.h>

#include <nlohmann/json.hpp>

#include <Eigen/Core>

#include <chrono>
#include <csignal>
#include <fstream>
#include <regex>
#include <thread>

#include <fcntl.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

using namespace tissuemesh;
using test::read_file;
using test::run_cli;

namespace {

/// Both solves end with a residual within 1e-6 of the load and a last correction within 1e-3 of
/// the displacement (model.analysis); Newton's last step leaves an error far below that correction.
/// Measured differences are below 1e-6 of the max displacement; 1e-4 keeps a margin while a wrong
/// material (a parameter applied to the wrong tissue or constant) differs by percents.
constexpr double kSameSolveRel = 1e-4;

std::vector<Eigen::Vector3d> displacement(const std::filesystem::path& vtu) {
  vtkNew<vtkXMLUnstructuredGridReader> reader;
  reader->SetFileName(vtu.string().c_str());
  reader->Update();
  vtkDataArray* a = reader->GetOutput()->GetPointData()->GetArray("displacement");
  std::vector<Eigen::Vector3d> u;
  if (!a) return u;
  u.resize(static_cast<std::size_t>(a->GetNumberOfTuples()));
  for (vtkIdType i = 0; i < a->GetNumberOfTuples(); ++i) a->GetTuple(i, u[i].data());
  return u;
}

struct Fixture {
  std::filesystem::path dir;
  std::string config_text;
  Fixture() {
    dir = test::scratch_dir() / "case";
    std::filesystem::create_directories(dir);
    // Samples are compared node by node with separate solves to kSameSolveRel of the largest
    // displacement: the solves must converge well below that. The config's 1e-3 bounds the last
    // correction's norm over all nodes, which lets a node held by a few small tets stay off by
    // more than kSameSolveRel.
    config_text = std::regex_replace(read_file(test::coarse_config(dir, "tet4")),
                                     std::regex("displacement_tolerance: 0\\.001"), "displacement_tolerance: 1.0e-07");
    EXPECT_NE(config_text.find("displacement_tolerance: 1.0e-07"), std::string::npos);
    std::ofstream(dir / "coarse.yaml") << config_text;
    EXPECT_EQ(run_cli("demo -c coarse.yaml --skip-calculix -o demo", dir).exit_code, 0);
    std::ofstream(dir / "grid.yaml") << "parameters:\n"
                                        "  materials.breast.mu: {range: [100 Pa, 400 Pa], scale: log}\n"
                                        "  materials.breast.K: {range: [20 kPa, 80 kPa]}\n"
                                        "design: {type: grid, levels: 3}\n"
                                        "save_fields: true\n";
  }
};

const Fixture& fixture() {
  static const Fixture f;
  return f;
}

TEST(Sweep, EverySampleEqualsASeparateSolve) {
  const Fixture& f = fixture();
  for (const std::string& variant : {"--jobs 1", "--jobs 2", "--jobs 1 --no-warm-start"}) {
    const std::string out = "grid" + std::to_string(std::hash<std::string>()(variant) % 1000);
    const auto r = run_cli("sweep demo/mesh.vtu -c coarse.yaml --sweep grid.yaml -o " + out + " " + variant, f.dir);
    ASSERT_EQ(r.exit_code, 0) << variant << "\n" << r.err << r.out;
    const std::string csv = read_file((f.dir / out / "results.csv").string());
    std::istringstream lines(csv);
    std::string line;
    std::getline(lines, line);  // header
    int rows = 0;
    double worst = 0.0;
    while (std::getline(lines, line)) {
      std::vector<std::string> cells;
      std::stringstream ss(line);
      std::string c;
      while (std::getline(ss, c, ',')) cells.push_back(c);
      const int sample = std::stoi(cells[0]);
      const double mu = std::stod(cells[2]), K = std::stod(cells[3]);
      // The same model through `solve`: the config with this sample's values.
      std::string text = std::regex_replace(f.config_text, std::regex("mu: 150 Pa"), "mu: " + cells[2] + " Pa");
      text = std::regex_replace(text, std::regex("K: 50 kPa"), "K: " + cells[3] + " Pa");
      const std::string cfg = out + "-" + std::to_string(sample) + ".yaml";
      std::ofstream(f.dir / cfg) << text;
      const auto s = run_cli("solve demo/mesh.vtu -c " + cfg + " -o " + out + "-solve" + std::to_string(sample), f.dir);
      ASSERT_EQ(s.exit_code, 0) << s.err;
      const auto a = displacement(f.dir / (out + "-solve" + std::to_string(sample)) / "solution.vtu");
      char name[16];
      std::snprintf(name, sizeof name, "%06d.vtu", sample);
      const auto b = displacement(f.dir / out / "fields" / name);
      ASSERT_EQ(a.size(), b.size()) << variant << " sample " << sample;
      double max_u = 0.0, diff = 0.0;
      for (std::size_t v = 0; v < a.size(); ++v) {
        max_u = std::max(max_u, a[v].norm());
        diff = std::max(diff, (a[v] - b[v]).norm());
      }
      EXPECT_LE(diff, kSameSolveRel * max_u) << variant << " sample " << sample << " (mu " << mu << ", K " << K << ")";
      worst = std::max(worst, diff / max_u);
      ++rows;
    }
    EXPECT_EQ(rows, 9) << variant;
    std::cout << "[ sweep    ] " << variant << ": 9 samples, largest difference from a separate solve " << worst
              << " of its max |u|\n";
  }
}

TEST(Sweep, KilledAndRerunEndsWithTheUninterruptedTable) {
  const Fixture& f = fixture();
  std::ofstream(f.dir / "lhs.yaml") << "parameters:\n"
                                       "  materials.breast.mu: {range: [100 Pa, 400 Pa], scale: log}\n"
                                       "  materials.breast.density: {range: [900 kg/m^3, 1100 kg/m^3]}\n"
                                       "design: {type: lhs, samples: 10, seed: 3}\n";
  ASSERT_EQ(run_cli("sweep demo/mesh.vtu -c coarse.yaml --sweep lhs.yaml -o whole", f.dir).exit_code, 0);
  // The same sweep, killed (SIGKILL) once three samples are on disk, then rerun.
  const pid_t child = fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    ASSERT_EQ(chdir(f.dir.c_str()), 0);
    execl(TISSUEMESH_EXE, TISSUEMESH_EXE, "sweep", "demo/mesh.vtu", "-c", "coarse.yaml", "--sweep", "lhs.yaml", "-o",
          "killed", static_cast<char*>(nullptr));
    _exit(127);
  }
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (!std::filesystem::exists(f.dir / "killed/samples/000002.json") && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  kill(child, SIGKILL);
  int status = 0;
  waitpid(child, &status, 0);
  ASSERT_TRUE(WIFSIGNALED(status)) << "the sweep ended before it could be killed";
  EXPECT_FALSE(std::filesystem::exists(f.dir / "killed/results.csv"));
  const auto r = run_cli("sweep demo/mesh.vtu -c coarse.yaml --sweep lhs.yaml -o killed", f.dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("finished before"), std::string::npos);
  EXPECT_EQ(read_file((f.dir / "killed/results.csv").string()), read_file((f.dir / "whole/results.csv").string()));
}

TEST(Sweep, ShardsMergedGiveTheLocalTable) {
  const Fixture& f = fixture();
  std::ofstream(f.dir / "small.yaml") << "parameters:\n"
                                         "  materials.breast.mu: {values: [120 Pa, 200 Pa, 300 Pa]}\n"
                                         "  model.gravity.acceleration: {range: [9.81 m/s^2, 14 m/s^2]}\n"
                                         "design: {type: grid, levels: 2}\n";
  const std::string base = "sweep demo/mesh.vtu -c coarse.yaml --sweep small.yaml --no-warm-start -o ";
  ASSERT_EQ(run_cli(base + "local", f.dir).exit_code, 0);
  for (int i = 1; i <= 3; ++i) {
    const auto r = run_cli(base + "sharded --shard " + std::to_string(i) + "/3", f.dir);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_FALSE(std::filesystem::exists(f.dir / "sharded/results.csv"));
  }
  ASSERT_EQ(run_cli(base + "sharded --merge", f.dir).exit_code, 0);
  EXPECT_EQ(read_file((f.dir / "sharded/results.csv").string()), read_file((f.dir / "local/results.csv").string()));
}

TEST(Sweep, SobolDesignReportsIndicesAndPlots) {
  const Fixture& f = fixture();
  std::ofstream(f.dir / "sobol.yaml") << "parameters:\n"
                                         "  materials.breast.mu: {range: [100 Pa, 300 Pa]}\n"
                                         "  materials.tumor.density: {range: [900 kg/m^3, 1100 kg/m^3]}\n"
                                         "design: {type: sobol, samples: 4, seed: 5}\n";
  ASSERT_EQ(run_cli("sweep demo/mesh.vtu -c coarse.yaml --sweep sobol.yaml -o sobol", f.dir).exit_code, 0);
  const nlohmann::json s = nlohmann::json::parse(read_file((f.dir / "sobol/summary.json").string()));
  EXPECT_EQ(s["samples"].get<int>(), 4 * (2 + 2));
  const nlohmann::json& max_u = s["outputs"][0];
  ASSERT_TRUE(max_u.contains("sobol_first") && max_u.contains("sobol_total"));
  // The breast's stiffness governs the sag far more than the tumour's density.
  EXPECT_GT(max_u["sobol_total"]["materials.breast.mu"].get<double>(),
            max_u["sobol_total"]["materials.tumor.density"].get<double>());
  EXPECT_TRUE(std::filesystem::exists(f.dir / "sobol/plots/max_displacement_mm__materials.breast.mu.svg"));
  // report.html plots the same indices: the page's data holds the first output's Sobol' totals.
  const std::string page = read_file((f.dir / "sobol/report.html").string());
  EXPECT_NE(page.find("\"Sensitivity of max_displacement_mm\""), std::string::npos);
  EXPECT_NE(page.find("\"Sobol' total\""), std::string::npos);
}

TEST(Sweep, BadSweepFilesAreRefusedByName) {
  const Fixture& f = fixture();
  const std::pair<const char*, const char*> cases[] = {
      {"materials.breast.modulus: {range: [1 Pa, 2 Pa]}", "materials.breast.modulus"},
      {"materials.liver.mu: {range: [1 Pa, 2 Pa]}", "liver"},
      {"materials.breast.mu: {range: [300 Pa, 100 Pa]}", "min > max"},
      {"materials.breast.mu: {range: [0 Pa, 100 Pa], scale: log}", "log scale"},
      {"materials.breast.K: {ratio_to: materials.fat.mu, range: [1, 2]}", "materials.fat.mu"},
      {"materials.breast.mu: {range: [100, 200]}", "materials.breast.mu"},
  };
  int n = 0;
  for (const auto& [line, culprit] : cases) {
    const std::string file = "bad" + std::to_string(n++) + ".yaml";
    std::ofstream(f.dir / file) << "parameters:\n  " << line << "\ndesign: {type: grid, levels: 2}\n";
    const auto r = run_cli("sweep demo/mesh.vtu -c coarse.yaml --sweep " + file + " -o bad" + std::to_string(n), f.dir);
    EXPECT_EQ(r.exit_code, 2) << line << "\n" << r.err;
    EXPECT_NE(r.err.find(culprit), std::string::npos) << line << "\n" << r.err;
    EXPECT_FALSE(std::filesystem::exists(f.dir / ("bad" + std::to_string(n)))) << line;
  }
  // A DIR made by another sweep file.
  ASSERT_EQ(run_cli("sweep demo/mesh.vtu -c coarse.yaml --sweep grid.yaml --no-warm-start -o taken", f.dir).exit_code, 0);
  std::ofstream(f.dir / "other.yaml") << "parameters:\n  materials.breast.mu: {values: [150 Pa]}\n";
  const auto r = run_cli("sweep demo/mesh.vtu -c coarse.yaml --sweep other.yaml -o taken", f.dir);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("sweep file"), std::string::npos) << r.err;
}

TEST(Sweep, ASampleWithoutAPhysicalMaterialIsAFailedRowNotAStoppedSweep) {
  const Fixture& f = fixture();
  std::ofstream(f.dir / "nu.yaml") << "parameters:\n  materials.breast.nu: {values: [0.45, 0.5]}\ndesign: {type: grid}\n";
  const auto r = run_cli("sweep demo/mesh.vtu -c coarse.yaml --sweep nu.yaml -o nu", f.dir);
  EXPECT_EQ(r.exit_code, 0) << r.err;  // the sweep ran; its table says which sample failed and why
  const std::string csv = read_file((f.dir / "nu/results.csv").string());
  EXPECT_NE(csv.find("0,,0.45,true"), std::string::npos) << csv;
  EXPECT_NE(csv.find("1,,0.5,false"), std::string::npos) << csv;
  EXPECT_NE(csv.find("Poisson's ratio must lie in (-1, 0.5)"), std::string::npos) << csv;
}

}  // namespace

TEST(Sweep, ShippedSweepFilesLoad) {
  const Fixture& f = fixture();
  for (const auto& e : std::filesystem::directory_iterator(std::string(TISSUEMESH_CONFIG_DIR) + "/sweeps")) {
    const auto r = run_cli("sweep demo/mesh.vtu -c " + std::string(TISSUEMESH_CONFIG_DIR) +
                               "/phantom.yaml --print-config --sweep " + e.path().string(), f.dir);
    EXPECT_EQ(r.exit_code, 0) << e.path() << "\n" << r.err;
    EXPECT_NE(r.out.find("design: {type:"), std::string::npos) << r.out;
  }
}

TEST(Sweep, LandmarksFollowEachSampleDisplacement) {
  // A landmark on a mesh node moves with that node: its position in results.csv is the node plus
  // the sample's displacement there (fields/NNNNNN.vtu, the model's node order = the mesh's with
  // node_order: mesh).
  const Fixture& f = fixture();
  std::ofstream(f.dir / "mesh-order.yaml") << std::regex_replace(f.config_text, std::regex("node_order: rcm"),
                                                                 "node_order: mesh");
  std::ofstream(f.dir / "two.yaml") << "parameters:\n  materials.breast.mu: {values: [120 Pa, 240 Pa]}\n"
                                       "design: {type: grid}\nsave_fields: true\n";
  vtkNew<vtkXMLUnstructuredGridReader> reader;
  reader->SetFileName((f.dir / "demo/mesh.vtu").string().c_str());
  reader->Update();
  double node[3];
  reader->GetOutput()->GetPoint(17, node);
  {
    std::ofstream points(f.dir / "points.csv");
    points.precision(17);
    points << "name,x,y,z\nmarker," << node[0] << "," << node[1] << "," << node[2] << "\n";
  }
  const auto r = run_cli("sweep demo/mesh.vtu -c mesh-order.yaml --sweep two.yaml -o marked --points points.csv", f.dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::istringstream csv(read_file((f.dir / "marked/results.csv").string()));
  std::string header, line;
  std::getline(csv, header);
  std::vector<std::string> names;
  {
    std::stringstream ss(header);
    std::string c;
    while (std::getline(ss, c, ',')) names.push_back(c);
  }
  const auto column = std::find(names.begin(), names.end(), "marker_x_mm") - names.begin();
  ASSERT_LT(column, static_cast<long>(names.size()));
  int rows = 0;
  while (std::getline(csv, line)) {
    std::vector<std::string> cells;
    std::stringstream ss(line);
    std::string c;
    while (std::getline(ss, c, ',')) cells.push_back(c);
    char name[16];
    std::snprintf(name, sizeof name, "%06d.vtu", std::stoi(cells[0]));
    const auto u = displacement(f.dir / "marked/fields" / name);
    for (int k = 0; k < 3; ++k)
      EXPECT_NEAR(std::stod(cells[column + k]), node[k] + u[17][k], 1e-6 * (1.0 + std::abs(node[k])));
    ++rows;
  }
  EXPECT_EQ(rows, 2);
}

TEST(Sweep, SigintFinishesTheRunningSampleAndARerunCompletes) {
  const Fixture& f = fixture();
  std::ofstream(f.dir / "many.yaml") << "parameters:\n  materials.breast.mu: {range: [100 Pa, 400 Pa]}\n"
                                        "design: {type: lhs, samples: 40, seed: 9}\nexport: [abaqus]\n";
  const pid_t child = fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    if (chdir(f.dir.c_str()) != 0) _exit(126);
    const int null = open("/dev/null", O_WRONLY);
    dup2(null, 1);
    dup2(null, 2);
    execl(TISSUEMESH_EXE, TISSUEMESH_EXE, "sweep", "demo/mesh.vtu", "-c", "coarse.yaml", "--sweep", "many.yaml", "-o",
          "stopped", static_cast<char*>(nullptr));
    _exit(127);
  }
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (!std::filesystem::exists(f.dir / "stopped/samples/000001.json") && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  kill(child, SIGINT);
  int status = 0;
  waitpid(child, &status, 0);
  ASSERT_TRUE(WIFEXITED(status)) << "the sweep did not end cleanly on SIGINT";
  EXPECT_EQ(WEXITSTATUS(status), 1);
  // What was written is whole: every sample file parses, and each converged one has its model.
  int kept = 0;
  for (const auto& e : std::filesystem::directory_iterator(f.dir / "stopped/samples")) {
    if (e.path().extension() != ".json") continue;
    EXPECT_NO_THROW(nlohmann::json::parse(read_file(e.path().string()))) << e.path();
    EXPECT_TRUE(std::filesystem::exists(f.dir / "stopped/models" / e.path().stem() / "model.inp")) << e.path();
    ++kept;
  }
  EXPECT_GE(kept, 2);
  EXPECT_LT(kept, 40);
  const auto r = run_cli("sweep demo/mesh.vtu -c coarse.yaml --sweep many.yaml -o stopped", f.dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json s = nlohmann::json::parse(read_file((f.dir / "stopped/summary.json").string()));
  EXPECT_EQ(s["converged"].get<int>(), 40);
}

TEST(Sweep, Prone2SupineAnalysisEqualsTheCommandPerSample) {
  // analysis: prone2supine runs the whole workflow per sample; its max prone-to-supine displacement
  // equals `tissuemesh prone2supine` with that sample's config.
  const Fixture& f = fixture();
  std::ofstream(f.dir / "p2s.yaml") << "parameters:\n  materials.breast.mu: {values: [150 Pa, 300 Pa]}\n"
                                       "design: {type: grid}\nanalysis: prone2supine\n";
  const auto r = run_cli("sweep demo/mesh.vtu -c coarse.yaml --sweep p2s.yaml -o p2s-sweep", f.dir);
  ASSERT_EQ(r.exit_code, 0) << r.err << r.out;
  const std::string csv = read_file((f.dir / "p2s-sweep/results.csv").string());
  for (const std::string& mu : {"150", "300"}) {
    std::ofstream(f.dir / ("p2s-" + mu + ".yaml"))
        << std::regex_replace(f.config_text, std::regex("mu: 150 Pa"), "mu: " + mu + " Pa");
    const auto c = run_cli("prone2supine demo/mesh.vtu -c p2s-" + mu + ".yaml -o p2s-cmd-" + mu, f.dir);
    ASSERT_EQ(c.exit_code, 0) << c.err;
    const nlohmann::json j = nlohmann::json::parse(read_file((f.dir / ("p2s-cmd-" + mu) / "prone2supine.json").string()));
    const double expected = j["max_displacement_prone_to_supine_mm"].get<double>();
    const std::smatch m = [&] {
      std::smatch found;
      std::regex_search(csv, found, std::regex("\n[01],," + mu + ",true,([0-9.e+-]+),"));
      return found;
    }();
    ASSERT_EQ(m.size(), 2u) << csv;
    EXPECT_NEAR(std::stod(m[1].str()), expected, 1e-6 * expected) << "mu " << mu;
    EXPECT_GT(expected, 10.0);
  }
}
