// The built-in static solver (solver_check/static_solver.h) on the hanging block of
// tests/support/model_fixture.h: equilibrium with the weight, direction of the sag, agreement with
// CalculiX on the same deck and energy, linear scaling at tiny loads, the growth of load
// increments, refusals.
#include "solver_check/static_solver.h"

#include "fe_export/abaqus/write_abaqus.h"
#include "solver_check/calculix_dat.h"
#include "solver_check/calculix_run.h"

#include "core/errors.h"
#include "support/model_fixture.h"
#include "support/test_paths.h"
#include "support/tolerances.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iostream>
#include <map>
#include <string>

namespace tissuemesh {
namespace {

Model block(ElementOrder order) {
  test::BlockModelOptions options;
  options.order = order;
  return test::block_model(options);
}

const char* name(ElementOrder order) { return order == ElementOrder::Linear ? "tet4" : "tet10"; }

double max_norm(const std::vector<Eigen::Vector3d>& u) {
  double m = 0.0;
  for (const Eigen::Vector3d& v : u) m = std::max(m, v.norm());
  return m;
}

void expect_no_nan(const SolveResult& r) {
  for (const Eigen::Vector3d& v : r.displacements) ASSERT_TRUE(v.allFinite());
  for (const NodeReaction& f : r.reactions) ASSERT_TRUE(f.force.allFinite());
  for (const StepRecord& s : r.steps)
    for (double n : s.residual_norms) ASSERT_TRUE(std::isfinite(n));
}

SolveResult solve_and_report(const Model& model, const std::string& what) {
  const SolveResult r = solve_static(model);
  std::cout << "[ solver   ] " << what << ": " << model.nodes.size() << " nodes, " << model.elements.size()
            << " elements, " << r.seconds << " s (assembly " << r.assembly_seconds << " s, linear solves "
            << r.linear_solve_seconds << " s, " << r.linear_solver << ", " << r.threads << " threads), " << r.message
            << "\n";
  ::testing::Test::RecordProperty("solver_seconds_" + what, std::to_string(r.seconds));
  return r;
}

/// The block solved once per order with the model's own settings, shared by the tests that only
/// read it (a tet10 solve takes tens of seconds with the simplicial factorisation).
const SolveResult& default_solve(ElementOrder order) {
  static std::map<ElementOrder, SolveResult> cache;
  auto it = cache.find(order);
  if (it == cache.end())
    it = cache.emplace(order, solve_and_report(block(order), std::string("default_") + name(order))).first;
  return it->second;
}

class Equilibrium : public ::testing::TestWithParam<ElementOrder> {};

TEST_P(Equilibrium, ReactionsBalanceTheWeight) {
  Model model = block(GetParam());
  model.analysis.residual_tolerance = test::kSolverTightResidualRel;
  const SolveResult r = solve_and_report(model, std::string("equilibrium_") + name(GetParam()));
  ASSERT_TRUE(r.converged) << r.message;
  expect_no_nan(r);
  EXPECT_EQ(r.load_fraction, 1.0);
  const double W = r.total_load.norm();
  // 800/600/600 mm^3 at 950/1040/1060 kg/m^3 = 2.02e-6 t, times 9810 mm/s^2 (N), along -y (prone).
  EXPECT_NEAR(W, 2.02e-6 * 9810, 2.02e-6 * 9810 * test::kRelativeRoundoff);
  EXPECT_LT(r.total_load.y(), 0.0);
  const Eigen::Vector3d imbalance = r.total_reaction + r.total_load;
  std::cout << "[ solver   ] weight " << W << " N, reaction " << r.total_reaction.transpose()
            << " N, relative imbalance " << imbalance.norm() / W << "\n";
  EXPECT_LE(imbalance.norm(), test::kSolverEquilibriumRel * W);
  EXPECT_EQ(r.reactions.size(), model.node_sets.at(0).nodes.size());
  for (const StepRecord& s : r.steps) {
    EXPECT_TRUE(s.accepted) << "no cut-back needed on the block: " << s.note;
    EXPECT_LE(s.residual_norms.back(), test::kSolverTightResidualRel);
  }
}

TEST_P(Equilibrium, NoTangentAtStepsPredictedToEndAnIncrement) {
  // Each Newton direction needs the tangent at its start point: at least one tangent per
  // iteration. Without the prediction every increment's last iterate got one too (iterations +
  // increments in all, on this block: no fallback restart, which would add one). A full step
  // predicted to end its increment is evaluated for the force alone, so fewer.
  const SolveResult& r = default_solve(GetParam());
  ASSERT_TRUE(r.converged) << r.message;
  std::cout << "[ solver   ] " << r.steps.size() << " increments, " << r.total_iterations << " iterations, "
            << r.tangent_assemblies << " tangent and " << r.force_assemblies << " force-only assemblies\n";
  EXPECT_GE(r.tangent_assemblies, r.total_iterations);
  EXPECT_LT(r.tangent_assemblies, r.total_iterations + static_cast<int>(r.steps.size()));
  EXPECT_GE(r.force_assemblies, r.total_iterations + static_cast<int>(r.steps.size()) - r.tangent_assemblies);
}

TEST_P(Equilibrium, FixedNodesStayAndTheAnteriorFaceSags) {
  const Model model = block(GetParam());
  const SolveResult& r = default_solve(GetParam());
  ASSERT_TRUE(r.converged) << r.message;
  ASSERT_EQ(r.displacements.size(), model.nodes.size());
  for (int v : model.node_sets.at(0).nodes) EXPECT_EQ(r.displacements[v], Eigen::Vector3d::Zero()) << v;
  const Eigen::Vector3d g = model.gravity.acceleration_m_s2.normalized();
  int anterior = 0;
  for (std::size_t i = 0; i < model.nodes.size(); ++i)
    if (model.nodes[i].y() == 0.0) {
      ++anterior;
      EXPECT_GT(r.displacements[i].dot(g), 0.0) << "node " << i << " moves along gravity";
    }
  EXPECT_GT(anterior, 0);
}

INSTANTIATE_TEST_SUITE_P(Block, Equilibrium, ::testing::Values(ElementOrder::Linear, ElementOrder::Quadratic),
                         [](const auto& info) { return std::string(name(info.param)); });

class AgainstCalculix : public ::testing::TestWithParam<ElementOrder> {
 protected:
  void SetUp() override {
    if (find_calculix().empty()) GTEST_SKIP() << "ccx not found (set TISSUEMESH_CCX or put ccx on PATH)";
  }
};

/// Runs ccx on `model`'s deck and checks the built-in result `r` against it (max nodal difference
/// within kCalculixSolutionRel of the max displacement); prints the figures.
void expect_same_as_calculix(const Model& model, const SolveResult& r, const std::string& job) {
  const std::filesystem::path inp = test::scratch_dir() / (job + ".inp");
  {
    std::ofstream out(inp);
    write_abaqus(model, out, {});
  }
  const CalculixRun run = run_calculix(inp.string(), 1);
  ASSERT_EQ(run.exit_code, 0) << run.log;
  const std::vector<DatBlock> blocks = read_calculix_dat(run.dat_path);
  const DatBlock& ccx = last_block(blocks, "displacements", "NALL");
  ASSERT_EQ(ccx.values.size(), model.nodes.size());

  ASSERT_TRUE(r.converged) << r.message;
  double max_u = 0.0, max_diff = 0.0, sum_diff = 0.0;
  for (std::size_t i = 0; i < model.nodes.size(); ++i) {
    const Eigen::Vector3d& c = ccx.values.at(static_cast<int>(i) + 1);
    max_u = std::max(max_u, c.norm());
    const double d = (c - r.displacements[i]).norm();
    max_diff = std::max(max_diff, d);
    sum_diff += d;
  }
  const double ratio = max_diff / max_u;
  std::cout << "[ solver   ] " << job << ": max |u| " << max_u << " mm (built-in " << max_norm(r.displacements)
            << "), max diff/max |u| " << ratio << ", mean diff/max |u| " << sum_diff / model.nodes.size() / max_u
            << "; ccx " << run.seconds << " s, built-in " << r.seconds << " s\n";
  ::testing::Test::RecordProperty("max_diff_ratio_" + job, std::to_string(ratio));
  ASSERT_GT(max_u, 0.0);
  EXPECT_LE(ratio, test::kCalculixSolutionRel);
}

TEST_P(AgainstCalculix, SameDisplacementsWithinOnePercent) {
  expect_same_as_calculix(block(GetParam()), default_solve(GetParam()),
                          std::string("solver_vs_ccx_") + name(GetParam()));
}

INSTANTIATE_TEST_SUITE_P(Block, AgainstCalculix, ::testing::Values(ElementOrder::Linear, ElementOrder::Quadratic),
                         [](const auto& info) { return std::string(name(info.param)); });

class SmallLoad : public ::testing::TestWithParam<ElementOrder> {};

TEST_P(SmallLoad, ScalesLinearly) {
  // One increment: the problem is linear to ~1e-6 here, Newton needs two iterations.
  Model model = block(GetParam());
  model.analysis.load_steps = 1;
  SolveOptions a, b;
  a.gravity_scale = 1e-6;
  b.gravity_scale = 3e-6;
  const SolveResult ra = solve_static(model, a), rb = solve_static(model, b);
  ASSERT_TRUE(ra.converged) << ra.message;
  ASSERT_TRUE(rb.converged) << rb.message;
  const double ua = max_norm(ra.displacements), ub = max_norm(rb.displacements);
  ASSERT_GT(ua, 0.0);
  std::cout << "[ solver   ] " << name(GetParam()) << " max |u| at 1e-6 g: " << ua << " mm, at 3e-6 g: " << ub
            << " mm, ratio " << ub / ua << "\n";
  EXPECT_NEAR(ub / ua, 3.0, 3.0 * test::kSmallLoadLinearityRel);
  // And node by node, not only the maximum.
  for (std::size_t i = 0; i < model.nodes.size(); ++i)
    EXPECT_LE((rb.displacements[i] - 3.0 * ra.displacements[i]).norm(), 3.0 * test::kSmallLoadLinearityRel * ua) << i;
}

INSTANTIATE_TEST_SUITE_P(Block, SmallLoad, ::testing::Values(ElementOrder::Linear, ElementOrder::Quadratic),
                         [](const auto& info) { return std::string(name(info.param)); });

// Load stepping (static_solver.h): under its own gravity the block converges every increment in
// at most 3 Newton iterations (3, 2, 2 when measured), so the next increment is four times as
// large, clipped to the rest of the load: 0.1, then 0.4 (to 0.5), then the remaining 0.5
// (doubling would give 0.1, 0.3, 0.7, 1.0).
TEST(LoadStepping, QuickIncrementsQuadrupleTheNextUpToTheRestOfTheLoad) {
  Model model = block(ElementOrder::Linear);
  model.analysis.load_steps = 10;
  const SolveResult r = solve_static(model);
  ASSERT_TRUE(r.converged) << r.message;
  for (std::size_t i = 0; i + 1 < r.steps.size(); ++i)  // the premise: quick increments
    ASSERT_LE(r.steps[i].iterations, 3) << "increment " << i + 1 << " to load " << r.steps[i].load_fraction;
  ASSERT_EQ(r.steps.size(), 3u);
  const double expected[] = {0.1, 0.5, 1.0};
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_TRUE(r.steps[i].accepted);
    // The targets are sums of increments: exact up to a few roundings.
    EXPECT_NEAR(r.steps[i].load_fraction, expected[i], test::kRelativeRoundoff) << i;
  }
}

// Right after a cut-back, a quick increment only doubles the next one (back to the size that
// failed), so failure and cut-back do not alternate at once. At 4 g with at most 3 Newton
// iterations the block's increments fail and are cut back several times (measured: 0.1, 0.4
// failed, 0.2 failed, 0.1, 0.2, ...); every increment accepted right after a failure is followed
// by one at most twice its size.
TEST(LoadStepping, AfterACutBackTheNextIncrementAtMostDoubles) {
  Model model = block(ElementOrder::Linear);
  model.analysis.load_steps = 10;
  model.analysis.max_newton_iterations = 3;
  SolveOptions options;
  options.gravity_scale = 4.0;
  const SolveResult r = solve_static(model, options);
  int checked = 0;
  for (std::size_t i = 1; i + 1 < r.steps.size(); ++i) {
    if (r.steps[i - 1].accepted || !r.steps[i].accepted) continue;
    ++checked;
    // Increments are halved and doubled: exact up to a few roundings.
    EXPECT_LE(r.steps[i + 1].increment, 2.0 * r.steps[i].increment * (1.0 + test::kRelativeRoundoff)) << i;
  }
  EXPECT_GT(checked, 0);  // the premise: a cut-back followed by an accepted increment and more
}

/// The message of the exception `solve_static(model)` throws, checked to be of type E.
template <class E>
std::string refusal(const Model& model) {
  try {
    solve_static(model);
  } catch (const E& e) {
    return e.what();
  } catch (const std::exception& e) {
    ADD_FAILURE() << "wrong exception type: " << e.what();
    return "";
  }
  ADD_FAILURE() << "not refused";
  return "";
}

TEST(Refusal, ModelWithoutFixedSet) {
  Model model = test::block_model();
  model.node_sets.clear();
  const std::string m = refusal<InputError>(model);
  EXPECT_NE(m.find("no fixed or sliding node set"), std::string::npos) << m;
}

TEST(Refusal, TissueWithZeroDensity) {
  Model model = test::block_model();
  model.materials.at(1).density_kg_m3 = 0.0;
  const std::string m = refusal<InputError>(model);
  EXPECT_NE(m.find(model.tissue_names.at(1)), std::string::npos) << m;
  EXPECT_NE(m.find("density"), std::string::npos) << m;
}

// The block with its top face (z = 10) on frictionless rollers: the top nodes stay in their plane,
// their reactions act along the normal only, the weight is still balanced, and CalculiX (the same
// constraint as *EQUATION) gives the same displacements.
class SlidingTop : public ::testing::Test {
 protected:
  static Model model() {
    test::BlockModelOptions options;
    options.sliding_top = true;
    return test::block_model(options);
  }
  static const SolveResult& solved() {
    static const SolveResult r = [] {
      Model m = model();
      m.analysis.residual_tolerance = test::kSolverTightResidualRel;
      return solve_and_report(m, "sliding_top_tet4");
    }();
    return r;
  }
};

TEST_F(SlidingTop, TopNodesStayInTheirPlaneAndReactAlongTheNormal) {
  const Model m = model();
  const SolveResult& r = solved();
  ASSERT_TRUE(r.converged) << r.message;
  expect_no_nan(r);
  const NodeSet& top = m.node_sets.at(1);
  ASSERT_EQ(top.constraint, Constraint::Sliding);
  const double scale = max_norm(r.displacements);
  ASSERT_GT(scale, 0.0);
  std::map<int, Eigen::Vector3d> reaction;
  for (const NodeReaction& f : r.reactions) reaction[f.node] = f.force;
  const std::vector<int>& fixed = m.node_sets.at(0).nodes;
  bool some_top_node_moves = false;
  for (int v : top.nodes) {
    // Exact constraint: n . u = 0 to round-off of the basis (unit vectors to ~1e-16).
    EXPECT_NEAR(r.displacements[v].z(), 0.0, test::kRelativeRoundoff * scale) << v;
    some_top_node_moves = some_top_node_moves || r.displacements[v].norm() > 0.1 * scale;
    if (std::binary_search(fixed.begin(), fixed.end(), v)) continue;  // also fixed: full reaction
    ASSERT_TRUE(reaction.count(v)) << v;
    EXPECT_NEAR(reaction[v].x(), 0.0, test::kRelativeRoundoff * r.total_load.norm()) << v;
    EXPECT_NEAR(reaction[v].y(), 0.0, test::kRelativeRoundoff * r.total_load.norm()) << v;
  }
  EXPECT_TRUE(some_top_node_moves) << "the rollers let the top face slide under gravity";
  const Eigen::Vector3d imbalance = r.total_reaction + r.total_load;
  std::cout << "[ solver   ] sliding top: relative imbalance " << imbalance.norm() / r.total_load.norm() << "\n";
  EXPECT_LE(imbalance.norm(), test::kSolverEquilibriumRel * r.total_load.norm());
}

TEST_F(SlidingTop, SameDisplacementsAsCalculix) {
  if (find_calculix().empty()) GTEST_SKIP() << "ccx not found (set TISSUEMESH_CCX or put ccx on PATH)";
  expect_same_as_calculix(model(), solved(), "solver_vs_ccx_sliding_tet4");
}

TEST(Failure, CutBacksThatCannotCureAreReportedWithoutNaN) {
  // 1e5 g on the soft block: far beyond what it can carry; with a tiny Newton budget and a large
  // minimum increment the solver must give up cleanly.
  Model model = test::block_model();
  model.analysis.max_newton_iterations = 2;
  model.analysis.min_step_fraction = 0.01;
  SolveOptions options;
  options.gravity_scale = 1e5;
  const SolveResult r = solve_static(model, options);
  EXPECT_FALSE(r.converged);
  EXPECT_FALSE(r.message.empty());
  EXPECT_LT(r.load_fraction, 1.0);
  ASSERT_FALSE(r.steps.empty());
  EXPECT_FALSE(r.steps.back().accepted);
  EXPECT_FALSE(r.steps.back().note.empty());
  expect_no_nan(r);
  std::cout << "[ solver   ] refused to finish: " << r.message << "\n";
}

}  // namespace
}  // namespace tissuemesh
