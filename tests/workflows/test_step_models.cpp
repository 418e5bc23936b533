// The models of the prone-to-supine steps (workflows/step_models.h): each step's constraints
// override the model's by set name, a set made sliding in any step carries normals, unknown names
// and box sets asked to slide are refused, and the supine step's sliding chest wall holds its
// nodes in the wall's plane.
#include "workflows/step_models.h"

#include "core/errors.h"
#include "core/model_builder.h"
#include "solver_check/static_solver.h"
#include "support/model_fixture.h"

#include <gtest/gtest.h>

namespace tissuemesh {
namespace {

Model build(const ModelSettings& settings) {
  return build_model(test::block_mesh(), settings, test::block_materials(false), "test fixture");
}

const NodeSet* find(const Model& m, const std::string& name) {
  for (const NodeSet& s : m.node_sets)
    if (s.name == name) return &s;
  return nullptr;
}

TEST(StepModels, EachStepHasItsOwnConstraintsAndTheSupineGravity) {
  const ModelSettings settings = test::block_settings({});  // chest_wall (plane y = 10) fixed
  Prone2SupineSettings p2s;
  p2s.supine_constraints["chest_wall"] = StepConstraint::Sliding;
  const Model base = build(settings_for_steps(settings, p2s));
  const Model unloading = unloading_model(base, settings, p2s);
  ASSERT_NE(find(unloading, "chest_wall"), nullptr);
  EXPECT_EQ(find(unloading, "chest_wall")->constraint, Constraint::Fixed);
  EXPECT_TRUE(find(unloading, "chest_wall")->normals.empty());
  EXPECT_EQ(unloading.gravity.acceleration_m_s2, base.gravity.acceleration_m_s2);

  std::vector<Eigen::Vector3d> moved = base.nodes;
  for (Eigen::Vector3d& p : moved) p.x() += 0.01 * p.y();
  const Model supine = supine_model(base, settings, p2s, moved);
  const NodeSet* wall = find(supine, "chest_wall");
  ASSERT_NE(wall, nullptr);
  EXPECT_EQ(wall->constraint, Constraint::Sliding);
  ASSERT_EQ(wall->normals.size(), wall->nodes.size());
  for (const Eigen::Vector3d& n : wall->normals) EXPECT_NEAR(std::abs(n.y()), 1.0, 1e-12);
  EXPECT_EQ(supine.nodes, moved);
  EXPECT_EQ(supine.gravity.acceleration_m_s2, Eigen::Vector3d(0.0, 9.81, 0.0));
  EXPECT_EQ(supine.gravity.name, "supine");

  // The sliding wall holds its nodes in its plane: u_y = 0 there, while they move along it.
  // Supine gravity would push the block into the wall; a tilted table also pulls it sideways.
  Model tilted = supine;
  tilted.gravity.acceleration_m_s2 = Eigen::Vector3d(4.0, 9.0, 0.0);
  tilted.node_sets.push_back({"side", Constraint::Fixed, {}, {}, "test"});  // the face x = 0 holds the rest
  for (std::size_t v = 0; v < tilted.nodes.size(); ++v)
    if (base.nodes[v].x() == 0.0) tilted.node_sets.back().nodes.push_back(static_cast<int>(v));
  const SolveResult r = solve_static(tilted);
  ASSERT_TRUE(r.converged) << r.message;
  double along = 0.0;
  for (int v : wall->nodes) {
    EXPECT_NEAR(r.displacements[v].y(), 0.0, 1e-12);  // mm-t-s: mm
    along = std::max(along, std::abs(r.displacements[v].x()));
  }
  EXPECT_GT(along, 0.01);
}

TEST(StepModels, AFreeSetConstrainsNothingInItsStep) {
  test::BlockModelOptions options;
  options.sliding_top = true;
  const ModelSettings settings = test::block_settings(options);
  Prone2SupineSettings p2s;
  p2s.supine_constraints["top"] = StepConstraint::Free;
  const Model base = build(settings_for_steps(settings, p2s));
  EXPECT_NE(find(unloading_model(base, settings, p2s), "top"), nullptr);
  EXPECT_EQ(find(supine_model(base, settings, p2s, base.nodes), "top"), nullptr);
}

TEST(StepModels, UnknownSetsAndSlidingBoxesAreRefusedByName) {
  ModelSettings settings = test::block_settings({});
  Prone2SupineSettings p2s;
  p2s.unloading_constraints["pectoralis"] = StepConstraint::Fixed;
  try {
    settings_for_steps(settings, p2s);
    FAIL() << "an unknown set was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("prone2supine.unloading.constraints: node set 'pectoralis'"),
              std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("chest_wall"), std::string::npos) << e.what();
  }
  NodeSetSettings box{"corner", {}, Constraint::Fixed};
  box.selection.kind = SetSelection::Kind::Box;
  box.selection.box_max_mm = {2, 2, 2};
  settings.node_sets.push_back(box);
  Prone2SupineSettings slide_box;
  slide_box.supine_constraints["corner"] = StepConstraint::Sliding;
  EXPECT_THROW(settings_for_steps(settings, slide_box), InputError);
}

}  // namespace
}  // namespace tissuemesh
