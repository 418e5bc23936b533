// TriangleGrid (surface/triangle_grid.h): a query sees an id in the cells of its current box only.
#include "surface/triangle_grid.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

using namespace tissuemesh;

namespace {

Eigen::AlignedBox3d box(double x0, double x1) { return {Eigen::Vector3d(x0, 0, 0), Eigen::Vector3d(x1, 0.5, 0.5)}; }
/// The grids' region: x in [-5, 6], one cell across in y and z.
const Eigen::AlignedBox3d kRegion(Eigen::Vector3d(-5.0, 0.0, 0.0), Eigen::Vector3d(6.0, 0.9, 0.9));

bool found(const TriangleGrid& g, const Eigen::AlignedBox3d& b, int id) {
  std::vector<int> out;
  g.query(b, out);
  return std::find(out.begin(), out.end(), id) != out.end();
}

}  // namespace

TEST(TriangleGrid, ReinsertMovesAnIdAndRemoveDropsIt) {
  TriangleGrid g;
  g.reset(1.0, kRegion);
  g.insert(7, box(0.1, 2.5));  // cells x = 0, 1, 2
  g.insert(8, box(5.1, 5.2));
  EXPECT_TRUE(found(g, box(2.2, 2.3), 7));
  EXPECT_FALSE(found(g, box(2.2, 2.3), 8));
  g.insert(7, box(-3.5, -3.2));  // moved: gone from its old cells
  EXPECT_FALSE(found(g, box(0.2, 2.9), 7));
  EXPECT_TRUE(found(g, box(-3.4, -3.3), 7));
  g.remove(7);
  g.remove(7);  // removing twice is harmless
  EXPECT_FALSE(found(g, box(-4.0, 6.0), 7));
  EXPECT_TRUE(found(g, box(-4.0, 6.0), 8));
}

TEST(TriangleGrid, ReinsertingIntoTheSameCellsKeepsOneEntryAndRemovedIdsComeBack) {
  TriangleGrid g;
  g.reset(1.0, kRegion);
  g.insert(3, box(0.1, 1.5));  // cells x = 0, 1
  g.insert(3, box(0.2, 1.4));  // the same cells: nothing changes
  std::vector<int> out;
  g.query(box(0.5, 0.6), out);  // cell x = 0 only
  EXPECT_EQ(std::count(out.begin(), out.end(), 3), 1);
  g.remove(3);
  EXPECT_FALSE(found(g, box(0.5, 0.6), 3));
  g.insert(3, box(0.1, 1.5));  // the cells it had before its removal: entered again
  EXPECT_TRUE(found(g, box(0.5, 0.6), 3));
  EXPECT_TRUE(found(g, box(1.2, 1.3), 3));
}

TEST(TriangleGrid, BoxesBeyondTheRegionAreFoundInItsBorderCells) {
  TriangleGrid g;
  g.reset(1.0, kRegion);
  g.insert(1, box(40.0, 41.0));  // far beyond x = 6: entered in the last column
  g.insert(2, box(-30.0, -29.5));
  EXPECT_TRUE(found(g, box(39.0, 39.5), 1));  // a query beyond the region reads the same border cells
  EXPECT_TRUE(found(g, box(6.2, 6.3), 1));    // and so does one in the last column, x in [6, 7)
  EXPECT_FALSE(found(g, box(5.5, 5.6), 1));
  EXPECT_TRUE(found(g, box(-4.9, -4.8), 2));
  EXPECT_EQ(g.slab_of(100.0, 0), 11);  // slabs -5 .. 6 along x
  EXPECT_EQ(g.slab_of(-100.0, 0), 0);
  EXPECT_EQ(g.slab_of(0.5, 0), 5);
  EXPECT_EQ(g.slab_of(0.5, 1), 0);  // one slab along y
}

TEST(TriangleGrid, AHugeRegionGetsLargerCells) {
  TriangleGrid g;
  g.reset(0.001, Eigen::AlignedBox3d(Eigen::Vector3d::Zero(), Eigen::Vector3d::Constant(100.0)));
  const double cells = std::pow(std::ceil(100.0 / g.cell()), 3);
  EXPECT_LE(cells, static_cast<double>(TriangleGrid::kMaxCells));
  EXPECT_GT(g.cell(), 0.001);
  g.insert(4, box(50.0, 50.1));
  EXPECT_TRUE(found(g, box(50.05, 50.06), 4));
}
