// `tissuemesh prone2supine` against a known truth on the coarse phantom: its mesh is taken as the
// unloaded state X*, solved under prone gravity (x = phi(X*)); given x alone, the command must give
// back X* and the supine shape of X* (the forward supine solve from X*), to 0.05 mm at every node.
// Naive reversal (the first iterate alone) is measured beside it. CalculiX runs the written supine
// model; landmarks map exactly; a landmark outside the mesh and a model too soft to converge fail
// as documented.
#include "cli/cli_runner.h"
#include "core/vtu_io.h"
#include "image/image_io.h"
#include "solver_check/calculix_dat.h"
#include "solver_check/calculix_run.h"
#include "support/test_paths.h"
#include "support/tolerances.h"

#include <gtest/gtest.h>
#include <vtkDataArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkSmartPointer.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLUnstructuredGridReader.h>

#include <nlohmann/json.hpp>

#include <fstream>
#include <regex>
#include <sstream>

using namespace tissuemesh;
using test::expect_no_nan_text;
using test::read_file;
using test::run_cli;

namespace {

/// The acceptance figure: max nodal error of the recovered reference and supine shapes.
constexpr double kRecoveredMm = 0.05;

vtkSmartPointer<vtkUnstructuredGrid> read_grid(const std::filesystem::path& path) {
  vtkNew<vtkXMLUnstructuredGridReader> reader;
  reader->SetFileName(path.string().c_str());
  reader->Update();
  return reader->GetOutput();
}

std::vector<Eigen::Vector3d> points_of(vtkUnstructuredGrid* grid) {
  std::vector<Eigen::Vector3d> p(static_cast<std::size_t>(grid->GetNumberOfPoints()));
  for (vtkIdType i = 0; i < grid->GetNumberOfPoints(); ++i) grid->GetPoint(i, p[i].data());
  return p;
}

std::vector<Eigen::Vector3d> vectors_of(vtkUnstructuredGrid* grid, const char* name) {
  vtkDataArray* a = grid->GetPointData()->GetArray(name);
  std::vector<Eigen::Vector3d> v;
  if (!a) return v;
  v.resize(static_cast<std::size_t>(a->GetNumberOfTuples()));
  for (vtkIdType i = 0; i < a->GetNumberOfTuples(); ++i) a->GetTuple(i, v[i].data());
  return v;
}

double max_distance(const std::vector<Eigen::Vector3d>& a, const std::vector<Eigen::Vector3d>& b) {
  EXPECT_EQ(a.size(), b.size());
  double m = 0.0;
  for (std::size_t i = 0; i < std::min(a.size(), b.size()); ++i) m = std::max(m, (a[i] - b[i]).norm());
  return m;
}

/// The truth and the command's runs on it, made once for all tests of this file.
struct Case {
  std::filesystem::path dir;
  std::string config, soft_config;
  std::vector<Eigen::Vector3d> truth, prone, supine_truth;
  test::CliResult run, naive;
  Case() {
    dir = test::scratch_dir() / "case";  // below the first test's folder, which no later test clears
    std::filesystem::create_directories(dir);
    // The model's node order is the mesh's, so solution.vtu's points are mesh.vtu's.
    std::string text = read_file(test::coarse_config(dir, "tet4"));
    text = std::regex_replace(text, std::regex("node_order: rcm"), "node_order: mesh");
    config = (dir / "coarse.yaml").string();
    std::ofstream(config) << text;
    std::ofstream(dir / "supine.yaml") << std::regex_replace(text, std::regex("direction: prone"), "direction: supine");
    std::ofstream(dir / "naive.yaml") << text << "prone2supine: {max_iterations: 1}\n";
    soft_config = (dir / "soft.yaml").string();
    std::ofstream(soft_config) << std::regex_replace(text, std::regex("mu: 150 Pa"), "mu: 0.05 Pa")
                               << "prone2supine: {max_iterations: 3}\n";

    EXPECT_EQ(run_cli("demo -c coarse.yaml --skip-calculix -o truth", dir).exit_code, 0);
    EXPECT_EQ(run_cli("solve truth/mesh.vtu -c supine.yaml -o supine_truth", dir).exit_code, 0);
    TetMesh mesh = read_vtu((dir / "truth/mesh.vtu").string());
    truth = mesh.points;
    const auto solved = read_grid(dir / "truth/solution.vtu");
    const std::vector<Eigen::Vector3d> u = vectors_of(solved, "displacement");
    const std::vector<Eigen::Vector3d> u_supine = vectors_of(read_grid(dir / "supine_truth/solution.vtu"), "displacement");
    EXPECT_EQ(u.size(), truth.size());
    EXPECT_EQ(u_supine.size(), truth.size());
    prone = truth;
    supine_truth = truth;
    for (std::size_t i = 0; i < std::min(u.size(), u_supine.size()); ++i) {
      prone[i] += u[i];
      supine_truth[i] += u_supine[i];
    }
    mesh.points = prone;
    write_vtu(mesh, (dir / "prone.vtu").string());
    // Landmarks: on node 17, inside the first tet (its centroid).
    {
      std::ofstream points(dir / "points.csv");
      points.precision(17);
      const Eigen::Vector3d centroid = 0.25 * (prone[mesh.tets[0][0]] + prone[mesh.tets[0][1]] +
                                               prone[mesh.tets[0][2]] + prone[mesh.tets[0][3]]);
      points << "name,x,y,z\non_node," << prone[17].x() << "," << prone[17].y() << "," << prone[17].z()
             << "\ninside," << centroid.x() << "," << centroid.y() << "," << centroid.z() << "\n";
    }
    run = run_cli("prone2supine prone.vtu -c coarse.yaml -o p2s --points points.csv", dir);
    naive = run_cli("prone2supine prone.vtu -c naive.yaml -o naive", dir);
  }
};

const Case& the_case() {
  static const Case c;
  return c;
}

TEST(Prone2Supine, RecoversTheKnownReferenceAndSupineShapes) {
  const Case& c = the_case();
  ASSERT_EQ(c.run.exit_code, 0) << c.run.err << c.run.out;
  const std::vector<Eigen::Vector3d> reference = read_vtu((c.dir / "p2s/reference.vtu").string()).points;
  const std::vector<Eigen::Vector3d> supine = points_of(read_grid(c.dir / "p2s/supine.vtu"));
  const double reference_error = max_distance(reference, c.truth);
  const double supine_error = max_distance(supine, c.supine_truth);
  // Naive reversal: the same command stopped after its first iterate (exit 1: not converged).
  EXPECT_EQ(c.naive.exit_code, 1) << c.naive.err;
  const double naive_reference_error =
      max_distance(read_vtu((c.dir / "naive/reference.vtu").string()).points, c.truth);
  const double naive_supine_error = max_distance(points_of(read_grid(c.dir / "naive/supine.vtu")), c.supine_truth);
  double sag = 0.0, supine_motion = 0.0;
  for (std::size_t i = 0; i < c.truth.size(); ++i) {
    sag = std::max(sag, (c.prone[i] - c.truth[i]).norm());
    supine_motion = std::max(supine_motion, (c.supine_truth[i] - c.prone[i]).norm());
  }
  std::cout << "[ p2s      ] coarse phantom: prone sag " << sag << " mm, prone to supine " << supine_motion
            << " mm; recovered reference max error " << reference_error << " mm, supine " << supine_error
            << " mm; naive reversal: reference " << naive_reference_error << " mm, supine " << naive_supine_error
            << " mm\n";
  ::testing::Test::RecordProperty("reference_error_mm", std::to_string(reference_error));
  ::testing::Test::RecordProperty("supine_error_mm", std::to_string(supine_error));
  ::testing::Test::RecordProperty("naive_reference_error_mm", std::to_string(naive_reference_error));
  ::testing::Test::RecordProperty("naive_supine_error_mm", std::to_string(naive_supine_error));
  EXPECT_GT(sag, 5.0);  // a real deformation, not a trivially small one
  EXPECT_LE(reference_error, kRecoveredMm);
  EXPECT_LE(supine_error, kRecoveredMm);
  EXPECT_GT(naive_reference_error, 10.0 * kRecoveredMm);
  EXPECT_GT(naive_supine_error, 10.0 * kRecoveredMm);
}

TEST(Prone2Supine, RecordAndFilesAreCompleteAndFinite) {
  const Case& c = the_case();
  ASSERT_EQ(c.run.exit_code, 0) << c.run.err;
  for (const char* f : {"reference.vtu", "supine.vtu", "prone_check.vtu", "supine_model.feb", "supine_model.inp",
                        "supine_model.scn", "supine_model.vtk", "points.csv", "prone2supine.json", "report.html"})
    EXPECT_TRUE(std::filesystem::exists(c.dir / "p2s" / f)) << f;
  const std::string text = read_file((c.dir / "p2s/prone2supine.json").string());
  expect_no_nan_text(text);
  const nlohmann::json j = nlohmann::json::parse(text);
  const nlohmann::json& rs = j["reference_state"];
  EXPECT_TRUE(rs["converged"].get<bool>());
  EXPECT_LE(rs["mismatch_mm"].get<double>(), 0.01);
  EXPECT_GT(rs["naive_reversal"]["mismatch_mm"].get<double>(), rs["mismatch_mm"].get<double>());
  ASSERT_GE(rs["iterations"].size(), 2u);
  for (const auto& it : rs["iterations"]) {
    EXPECT_TRUE(it.contains("alpha") && it.contains("newton_iterations") && it.contains("seconds"));
  }
  EXPECT_TRUE(j["supine_solve"]["converged"].get<bool>());
  bool tumour = false;
  for (const auto& t : j["tissues"]) {
    tumour = tumour || t["name"] == "tumor";
    EXPECT_NEAR(t["volume_change_reference_vs_prone_rel"].get<double>(), 0.0, 0.05) << t["name"];
  }
  EXPECT_TRUE(tumour);
  // prone_check.vtu: the reference loaded prone again reproduces the input within the tolerance.
  const auto check = read_grid(c.dir / "p2s/prone_check.vtu");
  const std::vector<Eigen::Vector3d> mismatch = vectors_of(check, "mismatch");
  ASSERT_FALSE(mismatch.empty());
  double worst = 0.0;
  for (const Eigen::Vector3d& m : mismatch) worst = std::max(worst, m.norm());
  EXPECT_LE(worst, 0.01 + 1e-9);
  // supine.vtu: its displacement arrays agree with its points.
  const auto supine = read_grid(c.dir / "p2s/supine.vtu");
  EXPECT_EQ(vectors_of(supine, "displacement_from_prone").size(), c.truth.size());
  EXPECT_EQ(vectors_of(supine, "displacement_from_reference").size(), c.truth.size());
}

TEST(Prone2Supine, CalculixRunsTheSupineModelAndAgrees) {
  if (find_calculix().empty()) GTEST_SKIP() << "ccx not found (set TISSUEMESH_CCX or put ccx on PATH)";
  const Case& c = the_case();
  ASSERT_EQ(c.run.exit_code, 0) << c.run.err;
  std::filesystem::create_directories(c.dir / "ccx");
  const std::filesystem::path job = c.dir / "ccx" / "supine_model.inp";
  std::filesystem::copy_file(c.dir / "p2s/supine_model.inp", job);
  const CalculixRun ccx = run_calculix(job.string(), 2);
  ASSERT_EQ(ccx.exit_code, 0) << ccx.log;
  const std::vector<DatBlock> blocks = read_calculix_dat(ccx.dat_path);
  const DatBlock& block = last_block(blocks, "displacements", "NALL");
  const std::vector<Eigen::Vector3d> builtin = vectors_of(read_grid(c.dir / "p2s/supine.vtu"), "displacement_from_reference");
  const std::vector<Eigen::Vector3d> theirs = values_by_node(block, builtin.size());  // mm-t-s: mm
  double max_u = 0.0;
  for (const Eigen::Vector3d& u : theirs) max_u = std::max(max_u, u.norm());
  const double diff = max_distance(theirs, builtin);
  std::cout << "[ p2s      ] supine step: CalculiX max |u| " << max_u << " mm, max difference " << diff / max_u
            << " of it\n";
  EXPECT_GT(max_u, 1.0);
  EXPECT_LE(diff, test::kCalculixSolutionRel * max_u);
}

TEST(Prone2Supine, LandmarksOnANodeAndInsideATet) {
  const Case& c = the_case();
  ASSERT_EQ(c.run.exit_code, 0) << c.run.err;
  const std::vector<Eigen::Vector3d> reference = read_vtu((c.dir / "p2s/reference.vtu").string()).points;
  const std::vector<Eigen::Vector3d> supine = points_of(read_grid(c.dir / "p2s/supine.vtu"));
  const TetMesh mesh = read_vtu((c.dir / "prone.vtu").string());
  std::istringstream csv(read_file((c.dir / "p2s/points.csv").string()));
  std::string line;
  std::getline(csv, line);  // header
  std::map<std::string, std::vector<double>> rows;
  while (std::getline(csv, line)) {
    std::stringstream ss(line);
    std::string name, field;
    std::getline(ss, name, ',');
    while (std::getline(ss, field, ',')) rows[name].push_back(std::atof(field.c_str()));
  }
  ASSERT_EQ(rows.size(), 2u);
  auto position = [&](const std::string& name, int first) {
    const std::vector<double>& r = rows.at(name);
    return Eigen::Vector3d(r[first], r[first + 1], r[first + 2]);
  };
  constexpr double kPrinted = 1e-6;  // points.csv has 6 decimals of a mm
  EXPECT_LE((position("on_node", 3) - reference[17]).norm(), kPrinted);
  EXPECT_LE((position("on_node", 6) - supine[17]).norm(), kPrinted);
  Eigen::Vector3d ref_centroid = Eigen::Vector3d::Zero(), sup_centroid = Eigen::Vector3d::Zero();
  for (int k = 0; k < 4; ++k) {
    ref_centroid += 0.25 * reference[mesh.tets[0][k]];
    sup_centroid += 0.25 * supine[mesh.tets[0][k]];
  }
  EXPECT_LE((position("inside", 3) - ref_centroid).norm(), kPrinted);
  EXPECT_LE((position("inside", 6) - sup_centroid).norm(), kPrinted);
}

TEST(Prone2Supine, ALandmarkOutsideTheMeshIsRefusedByName) {
  const Case& c = the_case();
  std::ofstream(c.dir / "outside.csv") << "nipple,0,-500,0\n";
  const auto r = run_cli("prone2supine prone.vtu -c coarse.yaml -o refused --points outside.csv", c.dir);
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("'nipple'"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(c.dir / "refused"));
}

TEST(Prone2Supine, TooSoftStopsWithExitOneTheBestIterateAndNoNaN) {
  const Case& c = the_case();
  const auto r = run_cli("prone2supine prone.vtu -c soft.yaml -o soft", c.dir);
  EXPECT_EQ(r.exit_code, 1) << r.err << r.out;
  EXPECT_NE(r.err.find("did not converge"), std::string::npos) << r.err;
  ASSERT_TRUE(std::filesystem::exists(c.dir / "soft/prone2supine.json"));
  const std::string text = read_file((c.dir / "soft/prone2supine.json").string());
  expect_no_nan_text(text);
  const nlohmann::json j = nlohmann::json::parse(text);
  EXPECT_FALSE(j["reference_state"]["converged"].get<bool>());
  for (const Eigen::Vector3d& p : read_vtu((c.dir / "soft/reference.vtu").string()).points) ASSERT_TRUE(p.allFinite());
}

TEST(Prone2Supine, LabelsCarriedIntoTheSupineShapeKeepTheTumour) {
  // The truth mesh and the image it was meshed from, taken as the prone pair: the carried tumour
  // keeps its voxel count (its volume changes < 1 %) and sits at the supine tumour centroid of the
  // record (to the voxel size).
  const Case& c = the_case();
  const auto r = run_cli("prone2supine truth/mesh.vtu -c coarse.yaml -o carried --image truth/phantom.nii.gz", c.dir);
  ASSERT_EQ(r.exit_code, 0) << r.err << r.out;
  const LabelImage prone = read_label_image((c.dir / "truth/phantom.nii.gz").string());
  const LabelImage supine = read_label_image((c.dir / "carried/supine_labels.nii.gz").string());
  EXPECT_LE((supine.spacing - prone.spacing).norm(), test::kHeaderCoordinateMm);
  const nlohmann::json j = nlohmann::json::parse(read_file((c.dir / "carried/prone2supine.json").string()));
  Eigen::Vector3d expected = Eigen::Vector3d::Zero();
  for (const auto& t : j["tissues"])
    if (t["name"] == "tumor")
      for (int a = 0; a < 3; ++a) expected[a] = t["centroid_supine_mm"][a].get<double>();
  auto tumour = [](const LabelImage& img, Eigen::Vector3d& centroid) {
    std::size_t n = 0;
    centroid.setZero();
    for (int k = 0; k < img.dims[2]; ++k)
      for (int jj = 0; jj < img.dims[1]; ++jj)
        for (int i = 0; i < img.dims[0]; ++i)
          if (img.at(i, jj, k) == 3) {
            ++n;
            centroid += img.to_physical(Eigen::Vector3d(i, jj, k));
          }
    if (n) centroid /= static_cast<double>(n);
    return n;
  };
  Eigen::Vector3d prone_centroid, supine_centroid;
  const std::size_t n_prone = tumour(prone, prone_centroid), n_supine = tumour(supine, supine_centroid);
  std::cout << "[ p2s      ] carried labels: tumour " << n_prone << " -> " << n_supine << " voxels, centroid "
            << (supine_centroid - expected).norm() << " mm from the record's supine tumour centroid (moved "
            << (supine_centroid - prone_centroid).norm() << " mm)\n";
  ASSERT_GT(n_prone, 100u);
  EXPECT_NEAR(static_cast<double>(n_supine), static_cast<double>(n_prone), 0.05 * n_prone);
  EXPECT_GT((supine_centroid - prone_centroid).norm(), 2.0);
  EXPECT_LE((supine_centroid - expected).norm(), prone.spacing.maxCoeff());
}

TEST(Prone2Supine, DemoFlagAddsTheStepWithTheTumourCentreAsLandmark) {
  const Case& c = the_case();
  const auto r = run_cli("demo -c coarse.yaml --skip-calculix --prone2supine -o demo", c.dir);
  ASSERT_EQ(r.exit_code, 0) << r.err << r.out;
  for (const char* f : {"mesh.vtu", "solution.vtu", "reference.vtu", "supine.vtu", "prone_check.vtu",
                        "supine_model.inp", "prone2supine.json", "landmarks.csv", "points.csv"})
    EXPECT_TRUE(std::filesystem::exists(c.dir / "demo" / f)) << f;
  const std::string points = read_file((c.dir / "demo/points.csv").string());
  EXPECT_NE(points.find("tumour_centre,"), std::string::npos) << points;
  EXPECT_NE(points.find(",tumor\n"), std::string::npos) << points;  // the centre lies in the tumour
}

}  // namespace
