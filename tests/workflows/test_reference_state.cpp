// The reference-state iteration (workflows/reference_state.h) against a manufactured truth: a
// model taken as the unloaded state X*, loaded by gravity (x = phi(X*)), must come back as X*
// from x alone; naive reversal must not (it is only the start). A model too soft to carry the
// load stops with a report and finite positions.
#include "workflows/reference_state.h"

#include "core/errors.h"
#include "support/model_fixture.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <iostream>

namespace tissuemesh {
namespace {

double max_distance(const std::vector<Eigen::Vector3d>& a, const std::vector<Eigen::Vector3d>& b, int n) {
  double m = 0.0;
  for (int v = 0; v < n; ++v) m = std::max(m, (a[v] - b[v]).norm());
  return m;
}

/// The truth and its loaded image: the block (tet4) under 3 g, so that the sag is a few mm.
struct Truth {
  Model unloaded, loaded;
  double sag_mm = 0.0;
  Truth() {
    unloaded = test::block_model();
    unloaded.gravity.acceleration_m_s2 *= 3.0;
    const SolveResult r = solve_static(unloaded);
    EXPECT_TRUE(r.converged) << r.message;
    std::vector<Eigen::Vector3d> x(unloaded.num_corner_nodes);
    for (int v = 0; v < unloaded.num_corner_nodes; ++v) {
      x[v] = unloaded.nodes[v] + r.displacements[v];  // mm-t-s: the length unit is mm
      sag_mm = std::max(sag_mm, r.displacements[v].norm());
    }
    loaded = with_corner_positions(unloaded, x);
  }
};

const Truth& truth() {
  static const Truth t;
  return t;
}

TEST(ReferenceState, RecoversTheManufacturedUnloadedShape) {
  const Truth& t = truth();
  ASSERT_GT(t.sag_mm, 1.0);
  ReferenceStateOptions options;
  options.tolerance_mm = 1e-3;
  const ReferenceStateResult r = estimate_reference_state(t.loaded, options, {});
  ASSERT_TRUE(r.converged) << r.message;
  const int n = t.unloaded.num_corner_nodes;
  const double error = max_distance(r.reference_nodes, t.unloaded.nodes, n);
  const double naive_error = max_distance(r.naive_nodes, t.unloaded.nodes, n);
  std::cout << "[ workflow ] sag " << t.sag_mm << " mm; reference error " << error << " mm after "
            << r.history.size() << " forward solves; naive reversal error " << naive_error << " mm\n";
  EXPECT_LE(r.mismatch_mm, options.tolerance_mm);
  // The error in X follows the mismatch through (I + du/dX)^-1: a few times the tolerance at most.
  EXPECT_LE(error, 5.0 * options.tolerance_mm);
  EXPECT_GT(naive_error, 20.0 * error);  // the reason for iterating
  EXPECT_TRUE(r.naive_measured);
  EXPECT_GT(r.naive_mismatch_mm, r.mismatch_mm);
  // Re-loading the reference reproduces the input to the tolerance.
  for (int v = 0; v < n; ++v)
    EXPECT_LE((r.reference_nodes[v] + r.loaded_displacements_mm[v] - t.loaded.nodes[v]).norm(),
              options.tolerance_mm + 1e-12);
}

TEST(ReferenceState, ForwardSolvesStartWarmAndTakeFewNewtonIterations) {
  ReferenceStateOptions options;
  options.tolerance_mm = 1e-3;
  const ReferenceStateResult r = estimate_reference_state(truth().loaded, options, {});
  ASSERT_GE(r.history.size(), 3u);
  ASSERT_TRUE(r.reversal.converged);
  int most = 0;
  for (const ReferenceIteration& it : r.history) {
    most = std::max(most, it.newton_iterations);
    EXPECT_EQ(it.increments, 1) << "forward solve " << it.index << " needed the ramp";
  }
  std::cout << "[ workflow ] naive reversal (a ramp from zero): " << r.reversal.total_iterations
            << " Newton iterations; forward solves: at most " << most << "\n";
  EXPECT_LT(most, r.reversal.total_iterations);
}

TEST(ReferenceState, FixedNodesKeepTheirImagedPosition) {
  const ReferenceStateResult r = estimate_reference_state(truth().loaded, {}, {});
  for (const NodeSet& set : truth().loaded.node_sets)
    for (int v : set.nodes) EXPECT_EQ(r.reference_nodes[v], truth().loaded.nodes[v]);
}

TEST(ReferenceState, TooSoftToCarryTheLoadStopsWithFinitePositions) {
  Model soft = truth().loaded;
  for (MaterialSpec& m : soft.materials) {
    m.mu_Pa *= 1e-4;
    m.C10_Pa *= 1e-4;
    m.C01_Pa *= 1e-4;
  }
  soft.analysis.max_load_steps = 20;
  ReferenceStateOptions options;
  options.max_iterations = 4;
  const ReferenceStateResult r = estimate_reference_state(soft, options, {});
  EXPECT_FALSE(r.converged);
  EXPECT_FALSE(r.message.empty());
  std::cout << "[ workflow ] too soft: " << r.message << "\n";
  ASSERT_EQ(r.reference_nodes.size(), soft.nodes.size());
  for (const Eigen::Vector3d& p : r.reference_nodes) EXPECT_TRUE(p.allFinite());
  for (const Eigen::Vector3d& u : r.loaded_displacements_mm) EXPECT_TRUE(u.allFinite());
}

TEST(ReferenceState, NoGravityIsRefused) {
  Model m = truth().loaded;
  m.gravity.acceleration_m_s2.setZero();
  EXPECT_THROW(estimate_reference_state(m, {}, {}), InputError);
}

TEST(ReferenceState, MidsideNodesStayAtTheirEdgesMidpoints) {
  test::BlockModelOptions tet10;
  tet10.order = ElementOrder::Quadratic;
  const Model block = test::block_model(tet10);
  std::vector<Eigen::Vector3d> corners(block.nodes.begin(), block.nodes.begin() + block.num_corner_nodes);
  for (Eigen::Vector3d& p : corners) p += Eigen::Vector3d(0.1 * p.y(), 0.0, 0.05 * p.x());
  const Model moved = with_corner_positions(block, corners);
  for (const auto& el : moved.elements) {
    EXPECT_NEAR((moved.nodes[el[4]] - 0.5 * (moved.nodes[el[0]] + moved.nodes[el[1]])).norm(), 0.0, 1e-12);
    EXPECT_NEAR((moved.nodes[el[9]] - 0.5 * (moved.nodes[el[2]] + moved.nodes[el[3]])).norm(), 0.0, 1e-12);
  }
}

}  // namespace
}  // namespace tissuemesh
