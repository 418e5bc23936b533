// FreeCellGrid (volume/free_cell_grid.h): no triangle meets a free cell, and all points of a
// component lie in one region. Checked on two nested cubes (tests/support/nested_cubes.h) whose
// large triangles cut the cells obliquely, plus needle and cap triangles, against an independent
// separating-axis test and the cubes' exact half-space test.
#include "volume/free_cell_grid.h"

#include "support/nested_cubes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

using namespace tissuemesh;
using tissuemesh::test::NestedCubes;

namespace {

// Separating-axis test of a triangle against a closed box (Akenine-Moller's 13 axes): true when
// no axis separates them strictly. A degenerate axis (parallel edges) never separates, so the
// test errs towards "overlap", the safe side for checking that free cells meet no triangle.
bool overlaps(const Eigen::Vector3d& a0, const Eigen::Vector3d& b0, const Eigen::Vector3d& c0,
              const Eigen::AlignedBox3d& box) {
  const Eigen::Vector3d centre = box.center(), half = 0.5 * box.sizes();
  const Eigen::Vector3d v[3] = {a0 - centre, b0 - centre, c0 - centre};
  const Eigen::Vector3d e[3] = {v[1] - v[0], v[2] - v[1], v[0] - v[2]};
  auto separates = [&](const Eigen::Vector3d& axis) {
    const double p0 = axis.dot(v[0]), p1 = axis.dot(v[1]), p2 = axis.dot(v[2]);
    const double r = half.cwiseProduct(axis.cwiseAbs()).sum();
    return std::min({p0, p1, p2}) > r || std::max({p0, p1, p2}) < -r;
  };
  for (int d = 0; d < 3; ++d)
    if (separates(Eigen::Vector3d::Unit(d))) return false;
  if (separates(e[0].cross(e[1]))) return false;
  for (const auto& edge : e)
    for (int d = 0; d < 3; ++d)
      if (separates(edge.cross(Eigen::Vector3d::Unit(d)))) return false;
  return true;
}

// Every free cell of `grid` (visited through their centres) against every triangle of `s`.
std::size_t free_cells_checked(const FreeCellGrid& grid, const TriSurface& s, const Eigen::Vector3d& low) {
  const double h = grid.cell_mm();
  const Eigen::Vector3d origin = grid.cell_box(low - Eigen::Vector3d::Constant(0.5 * h)).min();
  std::size_t free = 0;
  for (int k = 0;; ++k) {
    if (grid.cell_box(origin + h * Eigen::Vector3d(0.5, 0.5, k + 0.5)).isEmpty()) break;
    for (int j = 0;; ++j) {
      if (grid.cell_box(origin + h * Eigen::Vector3d(0.5, j + 0.5, k + 0.5)).isEmpty()) break;
      for (int i = 0;; ++i) {
        const Eigen::Vector3d x = origin + h * Eigen::Vector3d(i + 0.5, j + 0.5, k + 0.5);
        const Eigen::AlignedBox3d box = grid.cell_box(x);
        if (box.isEmpty()) break;
        if (grid.component(x) < 0) continue;
        ++free;
        for (const auto& t : s.triangles)
          EXPECT_FALSE(overlaps(s.points[t[0]], s.points[t[1]], s.points[t[2]], box))
              << "a triangle meets the free cell at " << x.transpose();
      }
    }
  }
  return free;
}

// The cubes plus two nearly collinear triangles across the grid whose computed normal is mostly
// rounding (at 45 to 60 degrees from the plane it should be perpendicular to): a corner on the
// segment between the two others (as rounded) but for one coordinate moved by one ulp.
TriSurface with_slivers(const NestedCubes& cubes) {
  TriSurface s = cubes.surface;
  const Eigen::Vector3d p = cubes.shift + Eigen::Vector3d(-31.3, -21.7, -24.1), q = p + Eigen::Vector3d(47.9, 43.3, 55.2);
  for (double t : {0.13, 0.37}) {
    const int n = static_cast<int>(s.points.size());
    Eigen::Vector3d c = p + t * (q - p);
    c.y() = std::nextafter(c.y(), 1e9);
    s.points.insert(s.points.end(), {p, q, c});
    s.triangles.push_back({n, n + 1, n + 2});
  }
  return s;
}

}  // namespace

TEST(FreeCellGrid, NoTriangleMeetsAFreeCell) {
  const NestedCubes cubes;
  const TriSurface s = with_slivers(cubes);
  const FreeCellGrid grid(s.points, s.triangles, 1.3);
  EXPECT_GT(free_cells_checked(grid, s, cubes.low()), 50000u);

  // Far from the origin, where rounding is coarser, and with a cell grown to fit a small grid.
  TriSurface moved = with_slivers(cubes);
  for (auto& p : moved.points) p += Eigen::Vector3d(1e5, -3e4, 2e5);
  const FreeCellGrid far_grid(moved.points, moved.triangles, 1.3);
  EXPECT_GT(free_cells_checked(far_grid, moved, cubes.low() + Eigen::Vector3d(1e5, -3e4, 2e5)), 50000u);
  const FreeCellGrid grown(s.points, s.triangles, 0.01, 20000);
  EXPECT_GT(grown.cell_mm(), 2.0);  // ~70 mm across in at most ~27 cells per axis
  EXPECT_GT(free_cells_checked(grown, s, cubes.low()), 1000u);
}

TEST(FreeCellGrid, EveryComponentLiesInOneRegion) {
  const NestedCubes cubes;
  const FreeCellGrid grid(cubes.surface.points, cubes.surface.triangles, 1.3);
  ASSERT_GE(grid.components(), 3u);  // outside, between, inside at least
  EXPECT_GT(grid.free_share(), 0.5);
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
  const FreeCellGrid grid(cubes.surface.points, cubes.surface.triangles, 1.3);
  EXPECT_EQ(grid.component(Eigen::Vector3d(500, 0, 0)), -1);
  EXPECT_TRUE(grid.cell_box(Eigen::Vector3d(500, 0, 0)).isEmpty());
  EXPECT_EQ(grid.component(Eigen::Vector3d(std::numeric_limits<double>::quiet_NaN(), 0, 0)), -1);
  // In the grid's one-cell border, beyond a corner of the cubes' box (far from the rotated cube):
  // free and outside.
  const int c = grid.component(cubes.low() - Eigen::Vector3d::Constant(1.0));
  ASSERT_GE(c, 0);
  EXPECT_EQ(cubes.region(grid.seed(static_cast<std::size_t>(c))), 0);
  // No cells at all: nothing is answered.
  const FreeCellGrid none(cubes.surface.points, cubes.surface.triangles, 1.3, 0);
  EXPECT_EQ(none.component(cubes.low() - Eigen::Vector3d::Constant(1.0)), -1);
  EXPECT_EQ(none.components(), 0u);
}

TEST(FreeCellGrid, AFreeSegmentNeverCrossesTheSurface) {
  const NestedCubes cubes;
  const FreeCellGrid grid(cubes.surface.points, cubes.surface.triangles, 1.3);
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
  const Eigen::Vector3d corner = cubes.low() - Eigen::Vector3d::Constant(1.0);
  EXPECT_TRUE(grid.segment_is_free(corner, corner + Eigen::Vector3d(0.1, 0.1, 0.1)));
  EXPECT_FALSE(grid.segment_is_free(corner, corner + Eigen::Vector3d(0.1, 0.1, 0.1), 0));
}
