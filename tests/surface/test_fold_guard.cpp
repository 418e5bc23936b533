// Folds of a remeshed surface (surface/surface_quality.h sharpest_fold_deg) and the remesher's
// fold guard (RemeshOptions::fold_guard): the sharpest fold is the smallest angle between two
// triangles of one patch across an edge; coarsening layers that fold faster than the edges can
// follow flattens some of them to a fraction of a degree, and the guard keeps every fold of the
// remeshed surface at 25.8 degrees or more (the 154-degree turn of RemeshComplex::kFoldCos).
#include "surface/surface_checks.h"
#include "surface/surface_projection.h"
#include "surface/surface_quality.h"
#include "surface/surface_remesh.h"
#include "support/surface_images.h"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

using namespace tissuemesh;
using namespace tissuemesh::test;

namespace {

// Triangle (0, 1, 2) and a second one across the edge 0-1, its apex turned by `turn_deg` from the
// first one's plane (0: flat, 180: folded onto it); labels {1, 0} for the first, `second` for the
// other.
TriSurface hinge(double turn_deg, std::array<int, 2> second) {
  const double t = turn_deg * M_PI / 180.0;
  TriSurface s;
  s.tissue_names = {"a", "b"};
  s.points = {{0, 0, 0}, {2, 0, 0}, {1, 1, 0}, {1, -std::cos(t), std::sin(t)}};
  s.triangles = {{0, 1, 2}, {1, 0, 3}};
  s.labels = {{1, 0}, second};
  return s;
}

}  // namespace

TEST(SurfaceFolds, SharpestFoldIsTheAngleBetweenTwoTrianglesOfOnePatch) {
  EXPECT_NEAR(sharpest_fold_deg(hinge(0.0, {1, 0})), 180.0, 1e-9);
  EXPECT_NEAR(sharpest_fold_deg(hinge(30.0, {1, 0})), 150.0, 1e-9);
  EXPECT_NEAR(sharpest_fold_deg(hinge(170.0, {1, 0})), 10.0, 1e-9);
  // Triangles of two patches meet at any angle (a tissue's corner): not a fold.
  EXPECT_NEAR(sharpest_fold_deg(hinge(170.0, {2, 0})), 180.0, 1e-9);
  // A closed surface: a regular tetrahedron's faces meet at acos(1/3) = 70.53 degrees.
  TriSurface tet;
  tet.tissue_names = {"a"};
  tet.points = {{1, 1, 1}, {1, -1, -1}, {-1, 1, -1}, {-1, -1, 1}};
  tet.triangles = {{0, 1, 2}, {0, 3, 1}, {0, 2, 3}, {1, 3, 2}};
  tet.labels.assign(4, {1, 0});
  EXPECT_NEAR(sharpest_fold_deg(tet), std::acos(1.0 / 3.0) * 180.0 / M_PI, 1e-9);
}

// Layers folding with a period of 3 voxels, remeshed to 4,000 vertices (edges of about 3.5 mm):
// without the guard some folds end up flat; with it none is sharper than the guard's limit, and
// the surface is valid and meets its budget.
TEST(SurfaceFolds, TheFoldGuardKeepsFoldsOpenOnLayersFoldingFasterThanTheEdges) {
  const LabelImage img = folds_every_three_voxels();
  const TriSurface input = extract(img, 7).surface;
  ASSERT_GT(sharpest_fold_deg(input), 30.0);  // the voxel surface, relaxed, has no sharp fold
  const SurfaceProjection on_input(input);
  RemeshOptions options;
  options.target_vertices = 4000;
  options.max_deviation_mm = 0.5 * img.spacing.norm();
  Progress quiet;
  const double unguarded = sharpest_fold_deg(remesh_surface(input, on_input, options, quiet).surface);
  ASSERT_LT(unguarded, 5.0) << "the unguarded remesh has no flat fold: nothing to test";
  options.fold_guard = true;
  const RemeshResult r = remesh_surface(input, on_input, options, quiet);
  const double guarded = sharpest_fold_deg(r.surface);
  std::cout << "[ folds    ] sharpest fold " << unguarded << " deg without the guard, " << guarded << " with it\n";
  EXPECT_GE(guarded, 180.0 - std::acos(-0.9) * 180.0 / M_PI - 1e-6);
  EXPECT_EQ(r.surface.points.size(), 4000u);
  EXPECT_TRUE(r.checks.valid());
}
