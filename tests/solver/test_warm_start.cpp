// Consecutive solves of one mesh (solver_check/static_solver.h): a solve that starts from a given
// displacement and a SolverWorkspace shared between solves reach the same equilibrium as a solve
// from scratch, and cost less; misuse is refused.
#include "solver_check/static_solver.h"

#include "core/errors.h"
#include "support/model_fixture.h"
#include "support/tolerances.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <iostream>
#include <stdexcept>

namespace tissuemesh {
namespace {

double max_difference(const std::vector<Eigen::Vector3d>& a, const std::vector<Eigen::Vector3d>& b) {
  double m = 0.0;
  for (std::size_t v = 0; v < a.size(); ++v) m = std::max(m, (a[v] - b[v]).norm());
  return m;
}

double max_norm(const std::vector<Eigen::Vector3d>& u) {
  double m = 0.0;
  for (const Eigen::Vector3d& v : u) m = std::max(m, v.norm());
  return m;
}

/// The block with tight Newton tolerances, so that two routes to one equilibrium agree well below
/// the comparison tolerance.
Model tight_block() {
  Model m = test::block_model();
  m.analysis.residual_tolerance = test::kSolverTightResidualRel;
  m.analysis.displacement_tolerance = 1e-8;
  return m;
}

const SolveResult& cold() {
  static const SolveResult r = solve_static(tight_block());
  return r;
}

TEST(WarmStart, FromTheSolutionOneIncrementSameEquilibrium) {
  ASSERT_TRUE(cold().converged) << cold().message;
  ASSERT_GT(cold().steps.size(), 1u);
  SolveOptions options;
  options.initial_displacements = cold().displacements;
  const SolveResult warm = solve_static(tight_block(), options);
  ASSERT_TRUE(warm.converged) << warm.message;
  ASSERT_EQ(warm.steps.size(), 1u);
  EXPECT_TRUE(warm.steps[0].accepted);
  EXPECT_LE(warm.total_iterations, 2);
  EXPECT_LT(warm.total_iterations, cold().total_iterations);
  std::cout << "[ solver   ] warm start from the solution: " << warm.total_iterations << " iterations (cold "
            << cold().total_iterations << "), difference "
            << max_difference(warm.displacements, cold().displacements) / max_norm(cold().displacements)
            << " of the max displacement\n";
  EXPECT_LE(max_difference(warm.displacements, cold().displacements),
            test::kSolverSameEquilibriumRel * max_norm(cold().displacements));
}

TEST(WarmStart, FromANearbyProblemSolutionFewerIterations) {
  // The block 5 % heavier: the lighter block's solution is a good start, not the answer.
  SolveOptions heavier;
  heavier.gravity_scale = 1.05;
  const SolveResult reference = solve_static(tight_block(), heavier);
  ASSERT_TRUE(reference.converged);
  heavier.initial_displacements = cold().displacements;
  const SolveResult warm = solve_static(tight_block(), heavier);
  ASSERT_TRUE(warm.converged) << warm.message;
  EXPECT_EQ(warm.steps.size(), 1u);
  EXPECT_LT(warm.total_iterations, reference.total_iterations);
  EXPECT_GT(max_difference(cold().displacements, reference.displacements), 0.01 * max_norm(reference.displacements));
  EXPECT_LE(max_difference(warm.displacements, reference.displacements),
            test::kSolverSameEquilibriumRel * max_norm(reference.displacements));
}

TEST(WarmStart, AStartThatInvertsElementsFallsBackToTheRamp) {
  std::vector<Eigen::Vector3d> wild(cold().displacements.size(), Eigen::Vector3d::Zero());
  for (std::size_t v = 0; v < wild.size(); v += 2) wild[v] = Eigen::Vector3d(40.0, -30.0, 25.0);  // folds the mesh
  SolveOptions options;
  options.initial_displacements = wild;
  const SolveResult r = solve_static(tight_block(), options);
  ASSERT_TRUE(r.converged) << r.message;
  ASSERT_GT(r.steps.size(), 1u);
  EXPECT_FALSE(r.steps[0].accepted);
  EXPECT_NE(r.steps[0].note.find("initial displacement"), std::string::npos) << r.steps[0].note;
  EXPECT_LE(max_difference(r.displacements, cold().displacements),
            test::kSolverSameEquilibriumRel * max_norm(cold().displacements));
}

TEST(WarmStart, WrongLengthOrNonFiniteIsRefused) {
  SolveOptions options;
  options.initial_displacements.assign(3, Eigen::Vector3d::Zero());
  EXPECT_THROW(solve_static(test::block_model(), options), InputError);
  options.initial_displacements.assign(test::block_model().nodes.size(), Eigen::Vector3d::Zero());
  options.initial_displacements[7].y() = std::nan("");
  EXPECT_THROW(solve_static(test::block_model(), options), InputError);
}

TEST(Workspace, SecondSolveSkipsTheAnalysisAndAgrees) {
  SolverWorkspace workspace;
  SolveOptions options;
  options.workspace = &workspace;
  const SolveResult first = solve_static(tight_block(), options);
  // Same mesh and constraints, other node positions (the block sheared by 1 mm over its height)
  // and a stiffer fat: what a reference-state iteration or a sweep changes between solves.
  Model moved = tight_block();
  for (Eigen::Vector3d& x : moved.nodes) x.x() += 0.1 * x.z();
  moved.materials[0].mu_Pa *= 2.0;
  moved.materials[0].C10_Pa *= 2.0;
  const SolveResult second = solve_static(moved, options);
  const SolveResult alone = solve_static(moved);
  ASSERT_TRUE(first.converged && second.converged && alone.converged);
  EXPECT_EQ(workspace.solves(), 2);
  EXPECT_GT(first.analysis_seconds, 0.0);
  EXPECT_EQ(second.analysis_seconds, 0.0);
  EXPECT_LE(second.factorisations, alone.factorisations);
  std::cout << "[ solver   ] shared workspace: " << second.factorisations << " factorisations (alone "
            << alone.factorisations << "), difference "
            << max_difference(second.displacements, alone.displacements) / max_norm(alone.displacements)
            << " of the max displacement\n";
  EXPECT_LE(max_difference(second.displacements, alone.displacements),
            test::kSolverSameEquilibriumRel * max_norm(alone.displacements));
}

TEST(Workspace, OtherUnknownsAreRefused) {
  SolverWorkspace workspace;
  SolveOptions options;
  options.workspace = &workspace;
  ASSERT_TRUE(solve_static(test::block_model(), options).converged);
  test::BlockModelOptions sliding;
  sliding.sliding_top = true;  // the same mesh with fewer unknowns
  EXPECT_THROW(solve_static(test::block_model(sliding), options), std::invalid_argument);
}

}  // namespace
}  // namespace tissuemesh
