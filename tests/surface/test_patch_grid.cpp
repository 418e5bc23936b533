// PatchGrid (surface/patch_grid.h): its closest point on a patch (and on any patch) is the one a
// search over every triangle of that patch (of the surface) finds, for points on, near and far
// from an extracted multi-material surface, on all of its patches; and SurfaceProjection::distance,
// which asks the grid near the surface and a box tree farther away, is that nearest distance.
#include "surface/patch_grid.h"
#include "surface/surface_projection.h"
#include "surface/triangle_geometry.h"
#include "support/surface_images.h"
#include "support/tolerances.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <random>

using namespace tissuemesh;
using namespace tissuemesh::test;

TEST(PatchGrid, ClosestPointIsTheNearestOfAllThePatchTriangles) {
  const TriSurface s = extract(three_boxes(), 3).surface;
  const PatchNumbering numbering = number_patches(s);
  std::vector<std::array<Eigen::Vector3d, 3>> tris;
  for (const auto& t : s.triangles) tris.push_back({s.points[t[0]], s.points[t[1]], s.points[t[2]]});
  const PatchGrid grid(tris, numbering.patch_of_triangle);
  ASSERT_GE(numbering.pair_of_patch.size(), 4u);  // the three boxes' interfaces and outer faces

  std::mt19937 rng(5);
  std::uniform_int_distribution<std::size_t> vertex(0, s.points.size() - 1);
  const SurfaceProjection projection(s);
  int queries = 0, far_queries = 0, beyond_one_shell = 0;
  for (double spread : {0.0, 0.3, 1.0, 3.0, 12.0}) {  // mm around surface vertices
    std::uniform_real_distribution<double> offset(-spread, spread);
    for (int k = 0; k < 60; ++k) {
      const Eigen::Vector3d p = s.points[vertex(rng)] + Eigen::Vector3d(offset(rng), offset(rng), offset(rng));
      for (int patch = 0; patch < static_cast<int>(numbering.pair_of_patch.size()); ++patch) {
        double brute = std::numeric_limits<double>::infinity();
        for (std::size_t t = 0; t < tris.size(); ++t)
          if (numbering.patch_of_triangle[t] == patch)
            brute = std::min(brute, (p - closest_point_on_triangle(p, tris[t][0], tris[t][1], tris[t][2])).squaredNorm());
        const PatchGrid::Hit hit = grid.closest(patch, p);
        ASSERT_GE(hit.triangle, 0);
        EXPECT_EQ(numbering.patch_of_triangle[static_cast<std::size_t>(hit.triangle)], patch);
        const auto& q = tris[static_cast<std::size_t>(hit.triangle)];
        // The same arithmetic on the same triangle (or one exactly as close): equal to the bit.
        EXPECT_EQ(hit.point, closest_point_on_triangle(p, q[0], q[1], q[2]));
        EXPECT_EQ((p - hit.point).squaredNorm(), brute) << "spread " << spread << ", patch " << patch;
        ++queries;
        far_queries += brute > 25.0;  // beyond 5 mm: several shells of cells searched
      }
      // Over every patch: the nearest of all triangles, which SurfaceProjection::distance returns.
      double brute = std::numeric_limits<double>::infinity();
      for (const auto& q : tris) brute = std::min(brute, (p - closest_point_on_triangle(p, q[0], q[1], q[2])).squaredNorm());
      const PatchGrid::Hit any = grid.closest_any(p);
      ASSERT_GE(any.triangle, 0);
      EXPECT_EQ((p - any.point).squaredNorm(), brute) << "spread " << spread << ", any patch";
      // Within one shell of cells around p's: the same point, or none when it lies farther.
      const PatchGrid::Hit near = grid.closest_any(p, 1);
      if (near.triangle >= 0)
        EXPECT_EQ((p - near.point).squaredNorm(), brute) << "spread " << spread << ", one shell";
      else
        ++beyond_one_shell;
      // SurfaceProjection::distance: the grid near the surface, a box tree far from it.
      EXPECT_NEAR(projection.distance(p), std::sqrt(brute), kRelativeRoundoff * (1.0 + std::sqrt(brute)));
    }
  }
  EXPECT_GT(far_queries, queries / 10);
  EXPECT_GT(beyond_one_shell, 0);  // both of distance()'s searches were tried
  EXPECT_LT(beyond_one_shell, 300);
}

TEST(PatchGrid, APatchWithoutTrianglesHasNoClosestPoint) {
  const std::vector<std::array<Eigen::Vector3d, 3>> tris{{Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(0, 1, 0)}};
  const PatchGrid grid(tris, {1});
  EXPECT_EQ(grid.closest(0, Eigen::Vector3d(0.2, 0.2, 1.0)).triangle, -1);
  EXPECT_EQ(grid.closest(2, Eigen::Vector3d(0.2, 0.2, 1.0)).triangle, -1);
  const PatchGrid::Hit hit = grid.closest(1, Eigen::Vector3d(0.2, 0.2, 1.0));
  EXPECT_EQ(hit.triangle, 0);
  EXPECT_LT((hit.point - Eigen::Vector3d(0.2, 0.2, 0.0)).norm(), kRelativeRoundoff);  // barycentric round-off
}

TEST(PatchGrid, ClosestPointOnADegenerateTriangleLiesOnItsEdges) {
  // Coincident or collinear corners: Ericson's edge and interior cases would divide by zero; the
  // closest point is then the nearest one on the triangle's edges.
  const Eigen::Vector3d a(0, 0, 0), b(2, 0, 0), p(1, 1, 0);
  EXPECT_LT((closest_point_on_triangle(p, a, a, b) - Eigen::Vector3d(1, 0, 0)).norm(), kRelativeRoundoff);
  EXPECT_LT((closest_point_on_triangle(p, a, Eigen::Vector3d(1, 0, 0), b) - Eigen::Vector3d(1, 0, 0)).norm(), kRelativeRoundoff);
  EXPECT_LT((closest_point_on_triangle(p, a, a, a) - a).norm(), kRelativeRoundoff);
  EXPECT_EQ(point_triangle_distance(Eigen::Vector3d(3, 0, 0), a, b, b), 1.0);
}

TEST(PatchGrid, RefusesAPatchListOfTheWrongSizeAndFindsNothingForANonFinitePoint) {
  const std::vector<std::array<Eigen::Vector3d, 3>> tris{{Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(0, 1, 0)}};
  EXPECT_THROW(PatchGrid(tris, {}), std::invalid_argument);
  EXPECT_THROW(PatchGrid(tris, {-1}), std::invalid_argument);
  const PatchGrid grid(tris, {0});
  EXPECT_EQ(grid.closest(0, Eigen::Vector3d(NAN, 0, 0)).triangle, -1);
  EXPECT_EQ(grid.closest_any(Eigen::Vector3d(0, NAN, 0)).triangle, -1);
  EXPECT_EQ(grid.closest(0, Eigen::Vector3d(1e300, -1e300, 0)).triangle, 0);  // far away, still found
  EXPECT_EQ(grid.closest_any(Eigen::Vector3d(-1e300, 0, 1e300)).triangle, 0);
  EXPECT_EQ(PatchGrid({}, {}).closest_any(Eigen::Vector3d(0, 0, 0)).triangle, -1);
}
