// The Abaqus deck solved by CalculiX itself: the block hangs from its posterior face under prone
// gravity; the displacements and the support reaction must be those of that physical problem.
// Skipped only when no ccx is found ($TISSUEMESH_CCX or PATH).
#include "fe_export/abaqus/write_abaqus.h"
#include "solver_check/calculix_dat.h"
#include "solver_check/calculix_run.h"

#include "core/errors.h"
#include "support/model_fixture.h"
#include "support/support_load.h"
#include "support/test_helpers.h"
#include "support/test_paths.h"
#include "support/tolerances.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <map>
#include <set>

namespace tissuemesh {
namespace {

/// Writes `model` as <scratch>/<job>.inp, runs ccx and returns the .dat blocks.
std::vector<DatBlock> solve(const Model& model, const std::string& job) {
  const std::filesystem::path inp = test::scratch_dir() / (job + ".inp");
  {
    std::ofstream out(inp);
    write_abaqus(model, out, {});
  }
  const CalculixRun run = run_calculix(inp.string(), 1);
  std::cout << "[ ccx      ] " << job << ": " << model.nodes.size() << " nodes, " << model.elements.size()
            << " elements, " << run.seconds << " s\n";
  ::testing::Test::RecordProperty("ccx_seconds_" + job, std::to_string(run.seconds));
  EXPECT_EQ(run.exit_code, 0) << run.log;
  EXPECT_EQ(run.log.find("*ERROR"), std::string::npos) << run.log;
  EXPECT_EQ(run.log.find("*WARNING"), std::string::npos) << run.log;
  return read_calculix_dat(run.dat_path);
}

/// What every block run must show; returns the final displacements.
std::map<int, Eigen::Vector3d> check_hanging_block(const Model& model, const std::vector<DatBlock>& blocks) {
  // The last displacement block is at the end of the step and covers every node.
  const DatBlock& u = last_block(blocks, "displacements", "NALL");
  EXPECT_EQ(u.time, 1.0);
  EXPECT_EQ(u.values.size(), model.nodes.size());
  if (u.values.size() != model.nodes.size()) return u.values;
  EXPECT_EQ(u.values.begin()->first, 1);
  EXPECT_EQ(u.values.rbegin()->first, static_cast<int>(model.nodes.size()));

  // Fixed (posterior, y = 10) nodes do not move; the free anterior face (y = 0) sags towards -y.
  const NodeSet& wall = model.node_sets.at(0);
  EXPECT_EQ(wall.name, "chest_wall");
  for (int v : wall.nodes) EXPECT_EQ(u.values.at(v + 1), Eigen::Vector3d::Zero()) << "node " << v + 1;
  int anterior = 0;
  for (std::size_t i = 0; i < model.nodes.size(); ++i)
    if (model.nodes[i].y() == 0.0) {
      ++anterior;
      EXPECT_LT(u.values.at(static_cast<int>(i) + 1).y(), 0.0) << "node " << i + 1;
    }
  EXPECT_GT(anterior, 0);

  // Support reaction = weight. ccx's RF is the internal force at the fixed nodes: the share of
  // the body load that sits on those nodes goes straight into the support and is not in it
  // (run: without it tet4 misses exactly W/10, tet10 W/30). The reaction on the body is then
  // RF - (load on the set), and equilibrium asks reaction + total load = 0.
  const DatBlock& rf = last_block(blocks, "forces", "CHEST_WALL");
  EXPECT_EQ(rf.time, 1.0);
  EXPECT_EQ(rf.values.size(), wall.nodes.size());
  EXPECT_TRUE(rf.has_total);
  Eigen::Vector3d sum = Eigen::Vector3d::Zero(), magnitude = Eigen::Vector3d::Zero();
  for (const auto& [id, f] : rf.values) {
    sum += f;
    magnitude += f.cwiseAbs();
  }
  for (int k = 0; k < 3; ++k)
    EXPECT_NEAR(rf.total[k], sum[k], test::kCalculixPrintRel * magnitude[k]) << "TOTALS = sum of the rows, " << k;
  const test::SupportLoad w = test::support_load(model, wall.nodes);
  const Eigen::Vector3d reaction = rf.total - w.on_set;
  const double W = w.total.norm();
  EXPECT_NEAR(W, 2.02e-6 * 9810, 2.02e-6 * 9810 * test::kRelativeRoundoff) << "800/600/600 mm^3 at 950/1040/1060 kg/m^3";
  EXPECT_NEAR(reaction.y(), -w.total.y(), test::kCalculixEquilibriumRel * W);
  EXPECT_NEAR(reaction.x(), -w.total.x(), test::kCalculixEquilibriumRel * W);
  // z as well unless a sliding plane (normal z: its constraint forces are not in RF) shares the load.
  if (model.node_sets.size() == 1) {
    EXPECT_NEAR(reaction.z(), -w.total.z(), test::kCalculixEquilibriumRel * W);
  }
  std::cout << "[ ccx      ] weight " << W << " N, support reaction " << reaction.transpose() << " N (relative error in x, y "
            << (reaction + w.total).head<2>().norm() / W << ")\n";
  return u.values;
}

class Calculix : public ::testing::Test {
 protected:
  void SetUp() override {
    if (find_calculix().empty()) GTEST_SKIP() << "ccx not found (set TISSUEMESH_CCX or put ccx on PATH)";
  }
};

TEST_F(Calculix, Tet4BlockHangsUnderItsWeight) {
  const Model model = test::block_model();
  check_hanging_block(model, solve(model, "block_tet4"));
}

TEST_F(Calculix, Tet10BlockHangsUnderItsWeight) {
  test::BlockModelOptions options;
  options.order = ElementOrder::Quadratic;
  const Model model = test::block_model(options);
  const auto u = check_hanging_block(model, solve(model, "block_tet10"));
  // tet10 is softer than the locking tet4: compare the largest sag with a tet4 run of the same block.
  const auto u4 = check_hanging_block(test::block_model(), solve(test::block_model(), "block_tet4"));
  double sag10 = 0.0, sag4 = 0.0;
  for (const auto& [id, v] : u) sag10 = std::max(sag10, -v.y());
  for (const auto& [id, v] : u4) sag4 = std::max(sag4, -v.y());
  std::cout << "[ ccx      ] largest sag: tet4 " << sag4 << " mm, tet10 " << sag10 << " mm\n";
  EXPECT_GT(sag10, sag4);
}

TEST_F(Calculix, OgdenTumor) {
  test::BlockModelOptions options;
  options.ogden_tumor = true;
  const Model model = test::block_model(options);
  check_hanging_block(model, solve(model, "block_ogden"));
}

void check_sliding(ElementOrder order, const std::string& job) {
  test::BlockModelOptions options;
  options.sliding_top = true;
  options.order = order;
  const Model model = test::block_model(options);
  const auto u = check_hanging_block(model, solve(model, job));
  if (u.size() != model.nodes.size()) return;
  const NodeSet& top = model.node_sets.at(1);
  ASSERT_EQ(top.constraint, Constraint::Sliding);
  double tangential = 0.0;
  for (std::size_t i = 0; i < top.nodes.size(); ++i) {
    const Eigen::Vector3d& v = u.at(top.nodes[i] + 1);
    EXPECT_LE(std::abs(top.normals[i].dot(v)), test::kCalculixPrintRel * v.norm()) << "node " << top.nodes[i] + 1;
    tangential = std::max(tangential, v.norm());
  }
  EXPECT_GT(tangential, 0.0) << "the sliding nodes do move, in their plane";
}

TEST_F(Calculix, SlidingTopKeepsItsNormalDisplacementZeroTet4) { check_sliding(ElementOrder::Linear, "sliding_tet4"); }

TEST_F(Calculix, SlidingTopKeepsItsNormalDisplacementZeroTet10) {
  check_sliding(ElementOrder::Quadratic, "sliding_tet10");
}

TEST_F(Calculix, SlidingAlongATiltedNormal) {
  // Two-term equations (normal (0, 0.6, 0.8), dependent DOF z): ccx must honour n . u = 0 with
  // both terms. The constraint forces now carry y, so only the constraint is checked here.
  test::BlockModelOptions options;
  options.sliding_top = true;
  Model model = test::block_model(options);
  const Eigen::Vector3d n(0.0, 0.6, 0.8);
  for (Eigen::Vector3d& normal : model.node_sets[1].normals) normal = n;
  const DatBlock& u = last_block(solve(model, "sliding_tilted"), "displacements", "NALL");
  ASSERT_EQ(u.values.size(), model.nodes.size());
  double moved = 0.0;
  for (int v : model.node_sets[1].nodes) {
    const Eigen::Vector3d& d = u.values.at(v + 1);
    EXPECT_LE(std::abs(n.dot(d)), test::kCalculixPrintRel * d.norm()) << "node " << v + 1;
    moved = std::max(moved, d.norm());
  }
  EXPECT_GT(moved, 0.0);
}

TEST(CalculixDat, RefusesAMissingFile) {
  EXPECT_THROW(read_calculix_dat("/nonexistent/job.dat"), InputError);
}

TEST(CalculixDat, ReadsBlocksTotalsAndFortranExponents) {
  const std::filesystem::path dat = test::scratch_dir() / "hand.dat";
  std::ofstream(dat) << "\n displacements (vx,vy,vz) for set NALL and time  0.5000000E+00\n\n"
                        "         1  0.000000E+00  1.000000E-01 -2.500000E+00\n"
                        "         2  1.000000-100  2.000000E+00  3.000000E+00 L\n\n"
                        " forces (fx,fy,fz) for set FIX and time  0.5000000E+00\n\n"
                        "         1  1.000000E+00  2.000000E+00  3.000000E+00\n\n"
                        " total force (fx,fy,fz) for set FIX and time  0.5000000E+00\n\n"
                        "        1.000000E+00  2.000000E+00  3.000000E+00\n\n"
                        " displacements (vx,vy,vz) for set NALL and time  0.1000000E+01\n\n"
                        "         1  0.000000E+00  2.000000E-01 -5.000000E+00\n"
                        "         2  0.000000E+00  4.000000E+00  6.000000E+00\n";
  const auto blocks = read_calculix_dat(dat.string());
  ASSERT_EQ(blocks.size(), 3u);
  EXPECT_EQ(blocks[0].values.at(2), Eigen::Vector3d(1e-100, 2.0, 3.0));
  EXPECT_TRUE(blocks[1].has_total);
  EXPECT_EQ(blocks[1].total, Eigen::Vector3d(1, 2, 3));
  EXPECT_FALSE(blocks[0].has_total);
  const DatBlock& last = last_block(blocks, "displacements", "nall");
  EXPECT_EQ(last.time, 1.0);
  EXPECT_EQ(last.values.at(1), Eigen::Vector3d(0.0, 0.2, -5.0));
  EXPECT_THROW(last_block(blocks, "displacements", "OTHER"), InputError);
  // Truncated after a header: an error naming the file.
  std::ofstream(dat) << " displacements (vx,vy,vz) for set NALL and time  0.1000000E+01\n\n";
  try {
    read_calculix_dat(dat.string());
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("hand.dat"), std::string::npos) << e.what();
  }
}

TEST(CalculixDat, ValuesByNodeNeedEveryNodeOnce) {
  DatBlock b;
  b.quantity = "displacements";
  b.set = "NALL";
  b.values = {{1, {1, 2, 3}}, {2, {4, 5, 6}}};
  const std::vector<Eigen::Vector3d> v = values_by_node(b, 2);
  ASSERT_EQ(v.size(), 2u);
  EXPECT_EQ(v[0], Eigen::Vector3d(1, 2, 3));
  EXPECT_EQ(v[1], Eigen::Vector3d(4, 5, 6));
  try {
    values_by_node(b, 3);
    FAIL() << "a missing node is refused";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("node 3 missing"), std::string::npos) << e.what();
  }
  EXPECT_THROW(values_by_node(b, 1), InputError) << "node 2 is not one of 1 nodes";
}

TEST_F(Calculix, ReportsABadDeckThroughExitCodeAndLog) {
  const std::filesystem::path inp = test::scratch_dir() / "bad.inp";
  std::ofstream(inp) << "*NODE\n1, 0, 0, 0\n*BOUNDARY\nNOSUCHSET, ENCASTRE\n";
  const CalculixRun run = run_calculix(inp.string(), 1);
  EXPECT_NE(run.exit_code, 0);
  EXPECT_NE(run.log.find("*ERROR"), std::string::npos) << run.log;
  EXPECT_EQ(test::read_file(inp.parent_path() / "bad.log"), run.log) << "log captured to <dir>/<job>.log";
  EXPECT_GT(run.seconds, 0.0);
}

TEST(CalculixRun, NoExecutableIsASolverError) {
  const std::filesystem::path inp = test::scratch_dir() / "job.inp";
  std::ofstream(inp) << "*NODE\n1, 0, 0, 0\n";
  const char* old = std::getenv("TISSUEMESH_CCX");
  const std::string saved = old ? old : "";
  ::setenv("TISSUEMESH_CCX", (inp.parent_path() / "no-such-ccx").c_str(), 1);
  EXPECT_EQ(find_calculix(), "");
  EXPECT_THROW(run_calculix(inp.string()), SolverError);
  if (old)
    ::setenv("TISSUEMESH_CCX", saved.c_str(), 1);
  else
    ::unsetenv("TISSUEMESH_CCX");
}

TEST(CalculixRun, RefusesADeckThatDoesNotExist) {
  EXPECT_THROW(run_calculix((test::scratch_dir() / "missing.inp").string()), InputError);
}

}  // namespace
}  // namespace tissuemesh
