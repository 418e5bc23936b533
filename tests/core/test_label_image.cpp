#include "core/errors.h"
#include "core/label_image.h"
#include "support/tolerances.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

using namespace tissuemesh;

namespace {
LabelImage small_image() {
  LabelImage img;
  img.dims = {3, 2, 2};
  img.spacing = {0.5, 1.0, 2.0};
  img.origin = {10, -20, 30};
  img.labels = {0, 1, 1, 2, 2, 2, 0, 0, 5, 5, 5, 5};
  return img;
}
}  // namespace

TEST(LabelImage, IndexIsXFastest) {
  LabelImage img = small_image();
  EXPECT_EQ(img.index(1, 0, 0), 1u);
  EXPECT_EQ(img.index(0, 1, 0), 3u);
  EXPECT_EQ(img.index(0, 0, 1), 6u);
  EXPECT_EQ(img.at(2, 1, 1), 5);
}

TEST(LabelImage, PhysicalPositionFollowsDirectionAndSpacing) {
  LabelImage img = small_image();
  img.direction = Eigen::AngleAxisd(0.3, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  const Eigen::Vector3d p = img.to_physical({2, 1, 1});
  const Eigen::Vector3d expected =
      img.origin + 2 * 0.5 * img.direction.col(0) + 1 * 1.0 * img.direction.col(1) + 1 * 2.0 * img.direction.col(2);
  EXPECT_LT((p - expected).norm(), test::kHeaderCoordinateMm);
  // Distances between voxel centres are the spacings, whatever the rotation.
  EXPECT_NEAR((img.to_physical({1, 0, 0}) - img.to_physical({0, 0, 0})).norm(), 0.5, 1e-12);
  EXPECT_NEAR((img.to_physical({0, 0, 1}) - img.to_physical({0, 0, 0})).norm(), 2.0, 1e-12);
}

TEST(LabelImage, CountsEveryLabel) {
  const auto counts = small_image().label_counts();
  EXPECT_EQ(counts.size(), 4u);
  EXPECT_EQ(counts.at(0), 3u);
  EXPECT_EQ(counts.at(1), 2u);
  EXPECT_EQ(counts.at(2), 3u);
  EXPECT_EQ(counts.at(5), 4u);
  EXPECT_DOUBLE_EQ(small_image().voxel_volume(), 1.0);
}

TEST(LabelImage, ValidateRejectsInconsistentGeometry) {
  LabelImage img = small_image();
  EXPECT_NO_THROW(img.validate("x"));
  img.labels.pop_back();
  EXPECT_THROW(img.validate("x"), InputError);
  img = small_image();
  img.spacing[1] = 0.0;
  EXPECT_THROW(img.validate("x"), InputError);
  img = small_image();
  img.direction(0, 1) = 0.5;  // not orthonormal
  EXPECT_THROW(img.validate("x"), InputError);
}

TEST(LabelImage, OrientationCode) {
  EXPECT_EQ(orientation_code(Eigen::Matrix3d::Identity()), "LPS");
  EXPECT_EQ(orientation_code(Eigen::Vector3d(-1, -1, 1).asDiagonal()), "RAS");
  Eigen::Matrix3d swapped;
  swapped << 0, 0, -1, 1, 0, 0, 0, -1, 0;  // i -> P, j -> I, k -> R
  EXPECT_EQ(orientation_code(swapped), "PIR");
}
