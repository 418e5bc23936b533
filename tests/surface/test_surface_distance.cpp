// Sampled Hausdorff distance (the surface pipeline's geometry figure): an analytic case whose
// maximum lies at an edge midpoint (not at a vertex, where the sampling starts), and agreement, bit
// for bit, with the plain maximum over every sample on a remeshed surface against its extraction.
#include "surface/surface_distance.h"
#include "support/complex_meshes.h"
#include "support/surface_images.h"
#include "support/tolerances.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

using namespace tissuemesh;
using namespace tissuemesh::test;

namespace {

TriSurface triangles(const std::vector<Eigen::Vector3d>& points, const std::vector<std::array<int, 3>>& tris) {
  TriSurface s;
  s.tissue_names = {"a"};
  s.points = points;
  s.triangles = tris;
  s.labels.assign(tris.size(), {0, 1});
  return s;
}

/// Every sample of hausdorff_distance (vertices, centroids, edge midpoints), each queried.
double all_samples_max(const TriSurface& from, const SurfaceProjection& to) {
  double d = 0.0;
  for (const auto& p : from.points) d = std::max(d, to.distance(p));
  for (const auto& t : from.triangles) {
    d = std::max(d, to.distance((from.points[t[0]] + from.points[t[1]] + from.points[t[2]]) / 3.0));
    for (int e = 0; e < 3; ++e) d = std::max(d, to.distance(0.5 * (from.points[t[e]] + from.points[t[(e + 1) % 3]])));
  }
  return d;
}

double vertices_max(const TriSurface& from, const SurfaceProjection& to) {
  double d = 0.0;
  for (const auto& p : from.points) d = std::max(d, to.distance(p));
  return d;
}

}  // namespace

TEST(SurfaceDistance, FindsAMaximumAwayFromTheVertices) {
  // A: the triangle (0,0), (30,0), (0,30) in z = 0. B: three small triangles in its corners. A's
  // vertices lie on B (distance 0); the farthest sample is the midpoint (15, 15) of A's long edge,
  // 14 sqrt(2) mm from B's corners (29, 1) and (1, 29). B lies inside A (distance 0).
  const TriSurface a = triangles({{0, 0, 0}, {30, 0, 0}, {0, 30, 0}}, {{0, 1, 2}});
  const TriSurface b = triangles({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {30, 0, 0}, {29, 1, 0}, {29, 0, 0}, {0, 30, 0},
                                  {0, 29, 0}, {1, 29, 0}},
                                 {{0, 1, 2}, {3, 4, 5}, {6, 7, 8}});
  const SurfaceProjection on_a(a), on_b(b);
  const SurfaceDistance d = hausdorff_distance(a, on_a, b, on_b);
  // Closest points on exact small coordinates: round-off only.
  EXPECT_NEAR(d.a_to_b_mm, 14.0 * std::sqrt(2.0), kRelativeRoundoff * 20.0);
  EXPECT_NEAR(d.b_to_a_mm, 0.0, kRelativeRoundoff);
  EXPECT_EQ(d.symmetric_mm(), d.a_to_b_mm);
}

TEST(SurfaceDistance, EqualsTheMaximumOverEverySample) {
  // Samples whose bound from their vertices rules them out are not queried: the result must still
  // be the maximum over all of them, exactly (the same closest-point queries, the same doubles).
  const LabelImage img = nested_spheres();
  const TriSurface input = extract(img, 2).surface;
  const SurfaceProjection on_input(input);
  const TriSurface remeshed_surface = remeshed(img, 2, 300).surface;
  const SurfaceProjection on_remeshed(remeshed_surface);
  const SurfaceDistance d = hausdorff_distance(remeshed_surface, on_remeshed, input, on_input);
  EXPECT_EQ(d.a_to_b_mm, all_samples_max(remeshed_surface, on_input));
  EXPECT_EQ(d.b_to_a_mm, all_samples_max(input, on_remeshed));
  EXPECT_GT(d.b_to_a_mm, 0.0);
  // On one thread: the same maxima (each thread skips by its own running maximum).
  const SurfaceDistance one = hausdorff_distance(remeshed_surface, on_remeshed, input, on_input, 1);
  EXPECT_EQ(one.a_to_b_mm, d.a_to_b_mm);
  EXPECT_EQ(one.b_to_a_mm, d.b_to_a_mm);
  EXPECT_THROW(hausdorff_distance(remeshed_surface, on_remeshed, input, on_input, 3), std::invalid_argument);
  // The remeshed surface's farthest sample is not a vertex (its vertices lie on the input), so
  // the result depends on the samples the bound may skip.
  EXPECT_GT(d.a_to_b_mm, vertices_max(remeshed_surface, on_input));
}
