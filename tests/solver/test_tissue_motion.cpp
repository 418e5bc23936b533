// Per-tissue volume-mean displacement (solver_check/tissue_motion.h) on the block of
// tests/support/model_fixture.h, whose tissues are boxes with known volumes and centroids: a
// translation moves every tissue by itself, u = A X moves each by A centroid; tet4 and tet10,
// displacements in mm and in metres.
#include "solver_check/tissue_motion.h"

#include "support/model_fixture.h"
#include "support/tolerances.h"

#include <gtest/gtest.h>

#include <functional>
#include <stdexcept>
#include <tuple>

namespace tissuemesh {
namespace {

// fat x in [0, 8], fgt [8, 14], tumor [14, 20]; y and z in [0, 10].
const double kVolume[3] = {800.0, 600.0, 600.0};
const Eigen::Vector3d kCentroid[3] = {{4, 5, 5}, {11, 5, 5}, {17, 5, 5}};

class TissueMotionTest : public ::testing::TestWithParam<std::tuple<ElementOrder, UnitSystem>> {
 protected:
  void SetUp() override {
    test::BlockModelOptions options;
    options.order = std::get<0>(GetParam());
    options.units = std::get<1>(GetParam());
    model = test::block_model(options);
  }
  /// A field given in mm, in the model's length unit.
  std::vector<Eigen::Vector3d> field(const std::function<Eigen::Vector3d(const Eigen::Vector3d&)>& u_mm) const {
    std::vector<Eigen::Vector3d> u;
    for (const Eigen::Vector3d& X : model.nodes) u.push_back(length_from_mm(model.units, 1.0) * u_mm(X));
    return u;
  }
  void expect_close(const Eigen::Vector3d& actual, const Eigen::Vector3d& expected) const {
    EXPECT_NEAR((actual - expected).norm(), 0.0, test::kRelativeRoundoff * expected.norm())
        << actual.transpose() << " vs " << expected.transpose();
  }
  Model model;
};

TEST_P(TissueMotionTest, TranslationMovesEveryTissueByIt) {
  const Eigen::Vector3d t(1.5, -2.0, 0.25);
  const MotionSummary m = tissue_motion(model, field([&](const Eigen::Vector3d&) { return t; }));
  ASSERT_EQ(m.tissues.size(), 3u);
  for (int i = 0; i < 3; ++i) {
    EXPECT_EQ(m.tissues[i].name, model.tissue_names[i]);
    EXPECT_NEAR(m.tissues[i].volume_mm3, kVolume[i], test::kRelativeRoundoff * kVolume[i]);
    expect_close(m.tissues[i].centroid_mm, kCentroid[i]);
    expect_close(m.tissues[i].mean_displacement_mm, t);
  }
  EXPECT_NEAR(m.max_displacement_mm, t.norm(), test::kRelativeRoundoff * t.norm());
}

TEST_P(TissueMotionTest, LinearFieldMovesEachTissueByItsCentroidImage) {
  Eigen::Matrix3d A;
  A << 0.1, -0.02, 0.03,  //
      0.05, 0.2, -0.01,   //
      0.0, 0.04, -0.15;
  const MotionSummary m = tissue_motion(model, field([&](const Eigen::Vector3d& X) { return A * X; }));
  for (int i = 0; i < 3; ++i) expect_close(m.tissues[i].mean_displacement_mm, A * kCentroid[i]);
}

TEST_P(TissueMotionTest, LargestNodalDisplacementAndItsNode) {
  std::vector<Eigen::Vector3d> u(model.nodes.size(), Eigen::Vector3d::Zero());
  const int peak = static_cast<int>(model.nodes.size()) - 2;
  u[peak] = length_from_mm(model.units, 1.0) * Eigen::Vector3d(0, 3, -4);
  u[7] = length_from_mm(model.units, 1.0) * Eigen::Vector3d(1, 0, 0);
  const MotionSummary m = tissue_motion(model, u);
  EXPECT_NEAR(m.max_displacement_mm, 5.0, 5.0 * test::kRelativeRoundoff);
  EXPECT_EQ(m.max_displacement_node, peak);
  // Ties: the lowest node index.
  EXPECT_EQ(tissue_motion(model, std::vector<Eigen::Vector3d>(model.nodes.size(), Eigen::Vector3d::Zero()))
                .max_displacement_node,
            0);
  EXPECT_THROW(tissue_motion(model, std::vector<Eigen::Vector3d>(2)), std::invalid_argument);
}

INSTANTIATE_TEST_SUITE_P(TissueMotion, TissueMotionTest,
                         ::testing::Combine(::testing::Values(ElementOrder::Linear, ElementOrder::Quadratic),
                                            ::testing::Values(UnitSystem::MillimetreTonneSecond, UnitSystem::SI)),
                         [](const auto& info) {
                           return test::order_units_name(std::get<0>(info.param), std::get<1>(info.param));
                         });

}  // namespace
}  // namespace tissuemesh
