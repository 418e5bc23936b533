// Tets TetGen leaves in no region (volume/unseeded_cells.h): a cell whose bounding surface
// triangles put it on a tissue's side becomes that tissue; one on the outside's side stays a
// cavity; other tets keep their ids.
#include "volume/unseeded_cells.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <map>

using namespace tissuemesh;

namespace {

// The unit cube (corners v = x + 2y + 4z, mm) in the 6 tets around its diagonal 0-7, and its 12
// boundary triangles, each oriented with its normal into the cube when `into_cube`, else out of it.
struct Cube {
  std::vector<Eigen::Vector3d> points;
  std::vector<std::array<int, 4>> tets;
  TriSurface surface;
};

Cube cube(bool into_cube, std::array<int, 2> labels) {
  Cube c;
  for (int v = 0; v < 8; ++v) c.points.emplace_back(v & 1, (v >> 1) & 1, (v >> 2) & 1);
  const int axes[6][3] = {{1, 2, 4}, {1, 4, 2}, {2, 1, 4}, {2, 4, 1}, {4, 1, 2}, {4, 2, 1}};
  for (const auto& a : axes) {
    std::array<int, 4> t = {0, a[0], a[0] + a[1], 7};
    const auto& p = c.points;
    if ((p[t[1]] - p[t[0]]).cross(p[t[2]] - p[t[0]]).dot(p[t[3]] - p[t[0]]) < 0) std::swap(t[2], t[3]);
    c.tets.push_back(t);
  }
  std::map<std::array<int, 3>, int> uses;
  for (const auto& t : c.tets)
    for (int q = 0; q < 4; ++q) {
      std::array<int, 3> f = {t[(q + 1) % 4], t[(q + 2) % 4], t[(q + 3) % 4]};
      std::sort(f.begin(), f.end());
      ++uses[f];
    }
  c.surface.tissue_names = {"a", "b"};
  c.surface.points = c.points;
  const Eigen::Vector3d centre(0.5, 0.5, 0.5);
  for (const auto& [f, n] : uses) {
    if (n != 1) continue;
    std::array<int, 3> w = f;
    const Eigen::Vector3d normal = (c.points[w[1]] - c.points[w[0]]).cross(c.points[w[2]] - c.points[w[0]]);
    if ((normal.dot(centre - c.points[w[0]]) > 0) != into_cube) std::swap(w[1], w[2]);
    c.surface.triangles.push_back(w);
    c.surface.labels.push_back(labels);
  }
  return c;
}

}  // namespace

TEST(UnseededCells, ACellOnATissuesSideBecomesThatTissue) {
  // Triangles p|q = 0|2 with their normals (from p into q) into the cube: the cube is tissue 2's.
  const Cube c = cube(true, {0, 2});
  ASSERT_EQ(c.surface.triangles.size(), 12u);
  std::vector<int> ids(6, 0);
  ids[5] = 1;  // a tet with a region keeps it
  const UnseededCells r = label_unseeded_cells(c.points, c.tets, c.surface, ids);
  EXPECT_EQ(r.tets, 5u);
  EXPECT_EQ(r.groups, 1u);
  EXPECT_NEAR(r.volume_mm3, 5.0 / 6.0, 1e-12);
  EXPECT_EQ(ids, (std::vector<int>{2, 2, 2, 2, 2, 1}));
}

TEST(UnseededCells, ACavityOfTheOutsideStaysACavity) {
  // The same triangles with their normals out of the cube: the cube is on the outside's side.
  const Cube c = cube(false, {0, 2});
  std::vector<int> ids(6, 0);
  const UnseededCells r = label_unseeded_cells(c.points, c.tets, c.surface, ids);
  EXPECT_EQ(r.tets, 0u);
  EXPECT_EQ(ids, std::vector<int>(6, 0));
}

TEST(UnseededCells, NothingToDoWhenEveryTetHasARegion) {
  const Cube c = cube(true, {0, 2});
  std::vector<int> ids(6, 1);
  EXPECT_EQ(label_unseeded_cells(c.points, c.tets, c.surface, ids).tets, 0u);
  EXPECT_EQ(ids, std::vector<int>(6, 1));
}
