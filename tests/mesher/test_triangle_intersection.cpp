// The remesher's intersection guard (mesher/triangle_intersection.h): the rule of CGAL's
// self_intersections for triangles of one surface, case by case, on exactly representable points
// (no tolerance: the predicates are exact).
#include "mesher/triangle_intersection.h"

#include <gtest/gtest.h>

using namespace tissuemesh;
using Eigen::Vector3d;

namespace {

TrianglePoints tri(Vector3d a, Vector3d b, Vector3d c) { return {a, b, c}; }

}  // namespace

TEST(TriangleIntersection, SeparateTrianglesWithoutSharedVertices) {
  const TrianglePoints a = tri({0, 0, 0}, {4, 0, 0}, {0, 4, 0});
  EXPECT_FALSE(triangles_intersect(a, {0, 1, 2}, tri({0, 0, 1}, {4, 0, 1}, {0, 4, 1}), {3, 4, 5}));  // parallel
  EXPECT_TRUE(triangles_intersect(a, {0, 1, 2}, tri({1, 1, -1}, {1, 1, 1}, {5, 5, 0}), {3, 4, 5}));  // pierces
  // Touching in one point (a vertex of b on a's interior) is an intersection: the shapes meet.
  EXPECT_TRUE(triangles_intersect(a, {0, 1, 2}, tri({1, 1, 0}, {1, 1, 2}, {2, 2, 2}), {3, 4, 5}));
}

TEST(TriangleIntersection, SharedVertexOnlyCountsTheOppositeEdges) {
  const TrianglePoints a = tri({0, 0, 0}, {4, 0, 0}, {0, 4, 0});
  // A fan neighbour meeting a only at vertex 0.
  EXPECT_FALSE(triangles_intersect(a, {0, 1, 2}, tri({0, 0, 0}, {-4, 0, 1}, {0, -4, 1}), {0, 5, 6}));
  // Folded back over a: its edge opposite the shared vertex cuts through a.
  EXPECT_TRUE(triangles_intersect(a, {0, 1, 2}, tri({0, 0, 0}, {2, 1, -1}, {1, 2, 1}), {0, 5, 6}));
  // The same points without the shared index: the common point alone is an intersection.
  EXPECT_TRUE(triangles_intersect(a, {0, 1, 2}, tri({0, 0, 0}, {-4, 0, 1}, {0, -4, 1}), {7, 5, 6}));
}

TEST(TriangleIntersection, SharedEdgeOnlyWhenFoldedFlatOntoEachOther) {
  const TrianglePoints a = tri({0, 0, 0}, {4, 0, 0}, {0, 4, 0});
  EXPECT_FALSE(triangles_intersect(a, {0, 1, 2}, tri({4, 0, 0}, {0, 0, 0}, {1, -3, 0}), {1, 0, 3}));  // flat, far side
  EXPECT_FALSE(triangles_intersect(a, {0, 1, 2}, tri({4, 0, 0}, {0, 0, 0}, {1, 3, 2}), {1, 0, 3}));   // a dihedral
  EXPECT_TRUE(triangles_intersect(a, {0, 1, 2}, tri({4, 0, 0}, {0, 0, 0}, {1, 1, 0}), {1, 0, 3}));    // folded flat
}

TEST(TriangleIntersection, TheSameTriangleTwiceIntersects) {
  const TrianglePoints a = tri({0, 0, 0}, {4, 0, 0}, {0, 4, 0});
  EXPECT_TRUE(triangles_intersect(a, {0, 1, 2}, tri({4, 0, 0}, {0, 4, 0}, {0, 0, 0}), {1, 2, 0}));
}
