// FreeCellGrid (mesher/free_cell_grid.h): no triangle passes through a free cell, and all points
// of a component lie in one region. Checked on two nested cubes, rotated so that their large
// triangles cut the grid cells obliquely, against exact half-space tests of the cubes.
#include "mesher/free_cell_grid.h"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

using namespace tissuemesh;

namespace {

struct NestedCubes {
  Eigen::Matrix3d rotation;
  double outer_half = 20, inner_half = 8;
  std::vector<Eigen::Vector3d> points;
  std::vector<std::array<int, 3>> triangles;

  NestedCubes() {
    rotation = (Eigen::AngleAxisd(0.4, Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(0.7, Eigen::Vector3d::UnitX()) *
                Eigen::AngleAxisd(0.2, Eigen::Vector3d::UnitY()))
                   .toRotationMatrix();
    add_cube(outer_half);
    add_cube(inner_half);
  }
  void add_cube(double h) {
    const int base = static_cast<int>(points.size());
    for (int c = 0; c < 8; ++c)
      points.push_back(rotation * Eigen::Vector3d(c & 1 ? h : -h, c & 2 ? h : -h, c & 4 ? h : -h) +
                       Eigen::Vector3d(3.1, -2.2, 0.7));
    // Two triangles per face (corner c has x = bit 0, y = bit 1, z = bit 2).
    const int faces[6][4] = {{0, 1, 3, 2}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 3, 7, 6}, {0, 2, 6, 4}, {1, 3, 7, 5}};
    for (const auto& f : faces) {
      triangles.push_back({base + f[0], base + f[1], base + f[2]});
      triangles.push_back({base + f[0], base + f[2], base + f[3]});
    }
  }
  // 0 outside, 1 between the cubes, 2 inside the inner one; -1 on a cube's boundary (exactly).
  int region(const Eigen::Vector3d& x) const {
    const Eigen::Vector3d local = rotation.transpose() * (x - Eigen::Vector3d(3.1, -2.2, 0.7));
    const double m = local.cwiseAbs().maxCoeff();
    if (m == inner_half || m == outer_half) return -1;
    return m < inner_half ? 2 : m < outer_half ? 1 : 0;
  }
};

}  // namespace

TEST(FreeCellGrid, EveryComponentLiesInOneRegionAndNoTriangleCrossesAFreeCell) {
  const NestedCubes cubes;
  const FreeCellGrid grid(cubes.points, cubes.triangles, 1.3);
  ASSERT_GE(grid.components(), 3u);  // outside, between, inside at least
  EXPECT_GT(grid.free_share(), 0.5);

  // Points on the triangles (a barycentric lattice, edges and corners included) are never in a
  // free cell.
  for (const auto& t : cubes.triangles)
    for (int i = 0; i <= 40; ++i)
      for (int j = 0; i + j <= 40; ++j) {
        const Eigen::Vector3d x = cubes.points[t[0]] + (i / 40.0) * (cubes.points[t[1]] - cubes.points[t[0]]) +
                                  (j / 40.0) * (cubes.points[t[2]] - cubes.points[t[0]]);
        ASSERT_EQ(grid.component(x), -1) << "a point of a triangle lies in a free cell";
      }

  // Random points of a free cell are in the region of their component's seed.
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> coordinate(-40, 40);
  std::size_t in_free = 0;
  for (int n = 0; n < 200000; ++n) {
    const Eigen::Vector3d x(coordinate(rng), coordinate(rng), coordinate(rng));
    const int c = grid.component(x);
    if (c < 0) continue;
    ++in_free;
    ASSERT_EQ(cubes.region(x), cubes.region(grid.seed(static_cast<std::size_t>(c)))) << "component " << c;
  }
  EXPECT_GT(in_free, 100000u);
}

TEST(FreeCellGrid, PointsOutsideTheGridOrNotFiniteAreNotAnswered) {
  const NestedCubes cubes;
  const FreeCellGrid grid(cubes.points, cubes.triangles, 1.3);
  EXPECT_EQ(grid.component(Eigen::Vector3d(500, 0, 0)), -1);
  EXPECT_EQ(grid.component(Eigen::Vector3d(std::numeric_limits<double>::quiet_NaN(), 0, 0)), -1);
  // In the grid's one-cell border, beyond a corner of the cubes' box (far from the rotated cube):
  // free and outside.
  Eigen::Vector3d low = cubes.points[0];
  for (const auto& p : cubes.points) low = low.cwiseMin(p);
  const int c = grid.component(low - Eigen::Vector3d::Constant(1.0));
  ASSERT_GE(c, 0);
  EXPECT_EQ(cubes.region(grid.seed(static_cast<std::size_t>(c))), 0);
}

TEST(FreeCellGrid, TheCellGrowsToKeepTheGridWithinItsLimit) {
  const NestedCubes cubes;
  const FreeCellGrid grid(cubes.points, cubes.triangles, 0.01, 100000);
  EXPECT_GT(grid.cell_mm(), 0.01);
  // The cubes' box is ~70 mm wide with the border: 100,000 cells give cells of at least ~1.5 mm.
  EXPECT_GT(grid.cell_mm(), 1.4);
}

TEST(FreeCellGrid, AFreeSegmentNeverCrossesTheSurface) {
  const NestedCubes cubes;
  const FreeCellGrid grid(cubes.points, cubes.triangles, 1.3);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> coordinate(-40, 40), offset(-6, 6);
  std::size_t free = 0, crossing_refused = 0;
  for (int n = 0; n < 100000; ++n) {
    const Eigen::Vector3d a(coordinate(rng), coordinate(rng), coordinate(rng));
    const Eigen::Vector3d b = a + Eigen::Vector3d(offset(rng), offset(rng), offset(rng));
    const int ra = cubes.region(a), rb = cubes.region(b);
    if (!grid.segment_is_free(a, b)) {
      crossing_refused += ra != rb;
      continue;
    }
    ++free;
    // Both ends in one region, and every point between them in a free cell of one component.
    ASSERT_EQ(ra, rb);
    const int c = grid.component(a);
    ASSERT_GE(c, 0);
    for (int i = 1; i <= 16; ++i) ASSERT_EQ(grid.component(a + (i / 16.0) * (b - a)), c);
  }
  EXPECT_GT(free, 10000u);
  EXPECT_GT(crossing_refused, 1000u);  // the segments that do cross were asked and refused
  // A segment leaving the grid, or spanning more cells than asked for, is not vouched for.
  EXPECT_FALSE(grid.segment_is_free(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(500, 0, 0)));
  Eigen::Vector3d low = cubes.points[0];
  for (const auto& p : cubes.points) low = low.cwiseMin(p);
  const Eigen::Vector3d corner = low - Eigen::Vector3d::Constant(1.0);
  EXPECT_TRUE(grid.segment_is_free(corner, corner + Eigen::Vector3d(0.1, 0.1, 0.1)));
  EXPECT_FALSE(grid.segment_is_free(corner, corner + Eigen::Vector3d(0.1, 0.1, 0.1), 0));
}
