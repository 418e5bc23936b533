// RemeshComplex::compact (mesher/remesh_complex.h): dropping the dead vertices and triangles
// keeps the live mesh, and every later sweep does exactly what it would have done without it.
#include "mesher/remesh_complex.h"
#include "support/surface_images.h"

#include <gtest/gtest.h>

using namespace tissuemesh;
using namespace tissuemesh::test;

namespace {

void expect_same(const TriSurface& a, const TriSurface& b) {
  EXPECT_EQ(a.points, b.points);  // bit for bit: the same operations in the same order
  EXPECT_EQ(a.triangles, b.triangles);
  EXPECT_EQ(a.labels, b.labels);
  EXPECT_EQ(a.junctions, b.junctions);
}

}  // namespace

TEST(RemeshCompact, KeepsTheLiveMeshAndWhatLaterSweepsDo) {
  const LabelImage img = nested_spheres();
  const TriSurface input = extract(img, 2).surface;
  const SurfaceProjection on(input);
  RemeshOptions options;
  options.max_deviation_mm = 0.5 * img.spacing.norm();
  RemeshComplex plain(input, on, options), compacted(input, on, options);
  for (RemeshComplex* m : {&plain, &compacted}) {
    m->L = 3.0 * img.spacing.maxCoeff();  // coarsening: most vertices and triangles die
    m->collapse_short();
  }
  ASSERT_GT(plain.collapses, input.points.size() / 2);
  const TriSurface before = compacted.result(input);
  compacted.compact();
  expect_same(compacted.result(input), before);
  // Sweeps visit in index order and break ties by index: the renumbering must keep both.
  for (RemeshComplex* m : {&plain, &compacted}) {
    m->collapse_short();
    m->split_long();
    m->flip_all();
    m->relax();
    m->flip_all();
  }
  EXPECT_EQ(plain.collapses, compacted.collapses);
  EXPECT_EQ(plain.flips, compacted.flips);
  expect_same(plain.result(input), compacted.result(input));
}
