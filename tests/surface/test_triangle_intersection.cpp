// The remesher's intersection guard (surface/triangle_intersection.h): the rule of CGAL's
// self_intersections for triangles of one surface, case by case, on exactly representable points
// (no tolerance: the predicates are exact).
#include "surface/triangle_intersection.h"

#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/intersections.h>
#include <gtest/gtest.h>

#include <cmath>
#include <random>

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
  // In a's plane, its far edge crossing a: coplanar far edges do not clear the pair.
  EXPECT_TRUE(triangles_intersect(a, {0, 1, 2}, tri({0, 0, 0}, {3, 3, 0}, {-1, 3, 0}), {0, 5, 6}));
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

TEST(TriangleIntersection, NearlyCoplanarCasesAgreeWithExactArithmetic) {
  // The guard decides a point's side of a plane in double arithmetic only when an error bound
  // proves the sign. Here the far edge of a fan neighbour lies in the other triangle's plane up
  // to round-off (its corners built from the plane's own vectors, then nudged by a few ulps), where
  // double arithmetic alone gets signs wrong; every answer must equal the rule evaluated with
  // exact rational arithmetic (CGAL's Epeck, an independent evaluation of the same rule).
  using Exact = CGAL::Exact_predicates_exact_constructions_kernel;
  auto ep = [](const Vector3d& p) { return Exact::Point_3(p.x(), p.y(), p.z()); };
  auto edge_meets = [&](const Vector3d& p, const Vector3d& q, const TrianglePoints& t) {
    return CGAL::do_intersect(Exact::Segment_3(ep(p), ep(q)), Exact::Triangle_3(ep(t[0]), ep(t[1]), ep(t[2])));
  };
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> coord(-50.0, 50.0), weight(-0.5, 1.5);
  std::uniform_int_distribution<int> ulps(-4, 4);
  int intersecting = 0, separate = 0;
  for (int k = 0; k < 20000; ++k) {
    const Vector3d s(coord(rng), coord(rng), coord(rng));
    const TrianglePoints b = tri(s, {coord(rng), coord(rng), coord(rng)}, {coord(rng), coord(rng), coord(rng)});
    auto on_plane = [&] {
      Vector3d p = s + weight(rng) * (b[1] - s) + weight(rng) * (b[2] - s);
      for (int i = 0; i < 3; ++i)
        for (int n = ulps(rng); n != 0; n += n > 0 ? -1 : 1) p[i] = std::nextafter(p[i], n > 0 ? INFINITY : -INFINITY);
      return p;
    };
    const TrianglePoints a = tri(s, on_plane(), on_plane());
    const bool exact = edge_meets(a[1], a[2], b) || edge_meets(b[1], b[2], a);
    ASSERT_EQ(triangles_intersect(a, {0, 1, 2}, b, {0, 3, 4}), exact) << "case " << k;
    (exact ? intersecting : separate) += 1;
  }
  // Both outcomes occur, so neither a guard that always says "intersect" nor one that never does passes.
  EXPECT_GT(intersecting, 1000);
  EXPECT_GT(separate, 1000);
}

TEST(TriangleIntersection, PlaneSideIsCgalsExactOrientation) {
  // PreparedTriangle::side against CGAL's exact orientation on points off the plane by 0-4 ulps per
  // coordinate (where the double filter must give way) and far off it (where it decides).
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> coord(-50.0, 50.0), weight(-0.5, 1.5), offset(-1.0, 1.0);
  std::uniform_int_distribution<int> ulps(-4, 4);
  int coplanar = 0, off_plane = 0;
  std::uniform_int_distribution<int> integer(-50, 50);
  auto on_tilted_plane = [&] {  // z = x + 2y with integers: exactly coplanar, exactly representable
    const double x = integer(rng), y = integer(rng);
    return Vector3d(x, y, x + 2.0 * y);
  };
  for (int k = 0; k < 20000; ++k) {
    TrianglePoints t = tri({coord(rng), coord(rng), coord(rng)}, {coord(rng), coord(rng), coord(rng)},
                           {coord(rng), coord(rng), coord(rng)});
    Vector3d p = t[0] + weight(rng) * (t[1] - t[0]) + weight(rng) * (t[2] - t[0]);
    if (k % 4 == 3)
      t = tri(on_tilted_plane(), on_tilted_plane(), on_tilted_plane()), p = on_tilted_plane();
    else if (k % 2)
      for (int i = 0; i < 3; ++i)
        for (int n = ulps(rng); n != 0; n += n > 0 ? -1 : 1) p[i] = std::nextafter(p[i], n > 0 ? INFINITY : -INFINITY);
    else
      p += Vector3d(offset(rng), offset(rng), offset(rng));
    using K = CGAL::Exact_predicates_inexact_constructions_kernel;
    auto kp = [](const Vector3d& v) { return K::Point_3(v.x(), v.y(), v.z()); };
    const int exact = static_cast<int>(CGAL::orientation(kp(t[0]), kp(t[1]), kp(t[2]), kp(p)));
    ASSERT_EQ(PreparedTriangle(t).side(p), exact) << "case " << k;
    (exact == 0 ? coplanar : off_plane) += 1;
  }
  EXPECT_GT(coplanar, 0);  // exactly coplanar points occur, so a filter that never says 0 fails
  // Edges so short that the double products underflow: the error bound no longer holds there,
  // and the answer must still be CGAL's (a review found a wrong sign before the underflow check).
  const double tiny = std::ldexp(1.0, -537);
  using K = CGAL::Exact_predicates_inexact_constructions_kernel;
  const TrianglePoints t = tri({0, 0, 0}, {tiny, tiny, 0}, {1.49 * tiny, 0.51 * tiny, 0.6 * tiny});
  for (const Vector3d& p : {Vector3d(1, 0, 1), Vector3d(1e200, 0, 1e200)})
    EXPECT_EQ(PreparedTriangle(t).side(p), static_cast<int>(CGAL::orientation(K::Point_3(0, 0, 0), K::Point_3(tiny, tiny, 0),
                                                                            K::Point_3(1.49 * tiny, 0.51 * tiny, 0.6 * tiny),
                                                                            K::Point_3(p.x(), p.y(), p.z()))));
  EXPECT_GT(off_plane, 10000);
}
