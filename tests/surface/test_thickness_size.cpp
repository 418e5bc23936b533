// ThicknessSize (surface/thickness_size.h): the remesher's size bound from the local thickness.
// A sheet three voxels thick between two thick tissues bounds the size at its interfaces to
// ratio x its thickness (with the floor), and nothing far from it; thin parts get edges that fit
// them in remesh_surface, coarsened by one factor when they would take more than half the budget.
#include "core/errors.h"
#include "surface/surface_checks.h"
#include "surface/surface_projection.h"
#include "surface/surface_remesh.h"
#include "surface/thickness_size.h"
#include "support/surface_images.h"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <limits>

using namespace tissuemesh;
using namespace tissuemesh::test;

namespace {

// 40 x 40 x 24 voxels of 0.5 mm, a one-voxel border of outside: tissue 1 below k = 11, a sheet of
// tissue 2 three voxels (1.5 mm) thick, tissue 3 above k = 14.
LabelImage sheet_image() {
  return make_image({40, 40, 24}, {0.5, 0.5, 0.5}, [](int i, int j, int k) {
    if (i < 1 || i >= 39 || j < 1 || j >= 39 || k < 1 || k >= 23) return 0;
    return k < 11 ? 1 : k < 14 ? 2 : 3;
  });
}

/// Mean edge length (mm) of the triangles between regions p and q (either order when `sheet`: the
/// patches 1|2 and 2|3; else every other patch).
double mean_edge(const TriSurface& s, bool sheet) {
  double sum = 0.0;
  std::size_t n = 0;
  for (std::size_t t = 0; t < s.triangles.size(); ++t) {
    const bool on_sheet = s.labels[t][0] == 2 || s.labels[t][1] == 2;
    if (on_sheet != sheet) continue;
    for (int e = 0; e < 3; ++e) sum += (s.points[s.triangles[t][(e + 1) % 3]] - s.points[s.triangles[t][e]]).norm();
    n += 3;
  }
  return sum / static_cast<double>(n);
}

/// The sheet image remeshed to `budget` vertices without and with the thickness bound (ratio 1).
struct UniformAndBounded {
  RemeshResult uniform, bounded;
};
UniformAndBounded remesh_sheet(int budget) {
  const LabelImage img = sheet_image();
  const TriSurface input = extract(img, 3).surface;
  const SurfaceProjection on(input);
  const ThicknessSize bound(img, 4.0, 1.0, 0.5);
  RemeshOptions options;
  options.target_vertices = budget;
  options.max_deviation_mm = 0.5 * img.spacing.norm();
  Progress progress;
  UniformAndBounded r;
  r.uniform = remesh_surface(input, on, options, progress);
  options.max_edge_mm = [&bound](const Eigen::Vector3d& p) { return bound(p); };
  r.bounded = remesh_surface(input, on, options, progress);
  return r;
}

}  // namespace

TEST(ThicknessSize, BoundsTheSizeByTheThicknessNearThinParts) {
  const LabelImage img = sheet_image();
  const ThicknessSize ratio1(img, 4.0, 1.0, 0.5), ratio_half(img, 4.0, 0.5, 0.5), floored(img, 4.0, 0.5, 1.0);
  // A point on the lower interface of the sheet (between voxel layers k = 10 and 11).
  const Eigen::Vector3d on_sheet = img.to_physical(Eigen::Vector3d(20.3, 20.3, 10.5));
  EXPECT_NEAR(ratio1(on_sheet), 1.5, 1e-6);
  EXPECT_NEAR(ratio_half(on_sheet), 0.75, 1e-6);
  EXPECT_NEAR(floored(on_sheet), 1.0, 1e-6);
  // In the middle of tissue 1 (5 mm thick, over the 4 mm cap) and outside the image: no bound.
  EXPECT_EQ(ratio1(img.to_physical(Eigen::Vector3d(20.3, 20.3, 5.5))), std::numeric_limits<double>::infinity());
  EXPECT_EQ(ratio1(img.to_physical(Eigen::Vector3d(-10.0, 20.0, 10.5))), std::numeric_limits<double>::infinity());
  EXPECT_GT(ratio1.thin_voxels(), 0u);
  EXPECT_THROW(ThicknessSize(img, 4.0, 0.0, 0.5), InputError);
  EXPECT_THROW(ThicknessSize(img, 0.0, 1.0, 0.5), InputError);
}

// At 600 vertices the uniform edge (about 2.1 mm) is longer than the sheet is thick: with the
// bound the sheet's interfaces get finer edges than the rest, the budget is still met exactly and
// the surface stays valid; the sheet would take more than half the budget at 1.5 mm, so the bound
// is scaled by a factor a little over 1 (about 1.1 by the area estimate).
TEST(ThicknessSize, ThinPartsGetEdgesThatFitThemWithinTheBudget) {
  const auto [uniform, bounded] = remesh_sheet(600);
  const double sheet_u = mean_edge(uniform.surface, true), rest_u = mean_edge(uniform.surface, false);
  const double sheet_b = mean_edge(bounded.surface, true), rest_b = mean_edge(bounded.surface, false);
  std::cout << "[ surface  ] mean edge sheet / rest: uniform " << sheet_u << " / " << rest_u << " mm, bounded "
            << sheet_b << " / " << rest_b << " mm, scale " << bounded.thickness_scale << "\n";
  EXPECT_EQ(uniform.thickness_scale, 1.0);
  EXPECT_GT(sheet_u, 0.85 * rest_u);
  EXPECT_EQ(bounded.surface.points.size(), 600u);
  EXPECT_TRUE(bounded.checks.valid());
  EXPECT_GT(bounded.thickness_scale, 1.0);
  EXPECT_LT(bounded.thickness_scale, 1.5);
  EXPECT_LT(sheet_b, 0.8 * rest_b);
  EXPECT_LT(sheet_b, 1.25 * 1.5 * bounded.thickness_scale);
}

// At 100 vertices the sheet would need a factor of about 2.7 on its bound to take half the budget:
// the bound no longer fits the sheet, so it is dropped (scale 0) and the result is the uniform one.
TEST(ThicknessSize, ABoundTheBudgetCannotAffordIsDropped) {
  const auto [uniform, bounded] = remesh_sheet(100);
  EXPECT_EQ(bounded.thickness_scale, 0.0) << "the bound was kept";
  EXPECT_EQ(bounded.surface.points, uniform.surface.points);
  EXPECT_EQ(bounded.surface.triangles, uniform.surface.triangles);
}
