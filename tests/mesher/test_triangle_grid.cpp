// TriangleGrid (mesher/triangle_grid.h): a query sees an id in the cells of its current box only.
#include "mesher/triangle_grid.h"

#include <gtest/gtest.h>

#include <algorithm>

using namespace tissuemesh;

namespace {

Eigen::AlignedBox3d box(double x0, double x1) { return {Eigen::Vector3d(x0, 0, 0), Eigen::Vector3d(x1, 0.5, 0.5)}; }

bool found(const TriangleGrid& g, const Eigen::AlignedBox3d& b, int id) {
  std::vector<int> out;
  g.query(b, out);
  return std::find(out.begin(), out.end(), id) != out.end();
}

}  // namespace

TEST(TriangleGrid, ReinsertMovesAnIdAndRemoveDropsIt) {
  TriangleGrid g;
  g.reset(1.0);
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
  g.reset(1.0);
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
