// The triangle geometry shared by the Table 1 figures and the remesher (surface/triangle_geometry.h):
// the remesher's one-angle shortcuts give the angles the full formula gives.
#include "surface/triangle_geometry.h"
#include "support/tolerances.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

using namespace tissuemesh;
using namespace tissuemesh::test;
using Eigen::Vector3d;

TEST(TriangleGeometry, OneAngleShortcutsMatchAllThreeAngles) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> coordinate(-10.0, 10.0);
  auto point = [&] { return Vector3d(coordinate(rng), coordinate(rng), coordinate(rng)); };
  for (int k = 0; k < 10000; ++k) {
    const Vector3d a = point(), b = point();
    // Every third triangle a sliver: c near the line ab, so one angle is tiny and two near-equal
    // dot products compete for the smallest.
    const Vector3d c = k % 3 == 0 ? a + 0.5 * (b - a) + 1e-3 * point() : point();
    const auto angles = triangle_angles(a, b, c);
    EXPECT_EQ(angle_at_c(a, b, c), angles[2]);  // the same formula, so the same double
    // atan2 falls as its second argument grows; one ulp of atan2's error apart at most.
    EXPECT_NEAR(min_angle(a, b, c), *std::min_element(angles.begin(), angles.end()), kAtan2Rad);
  }
  const Vector3d p(1.0, 2.0, 3.0);
  EXPECT_EQ(min_angle(p, p, Vector3d(4.0, 5.0, 6.0)), 0.0);  // zero area
  EXPECT_EQ(angle_at_c(p, p, Vector3d(4.0, 5.0, 6.0)), 0.0);
  // The equilateral triangle: 60 degrees.
  EXPECT_NEAR(min_angle(Vector3d(0, 0, 0), Vector3d(1, 0, 0), Vector3d(0.5, std::sqrt(0.75), 0)) * 180.0 / M_PI, 60.0,
              kAngleDeg);
}
