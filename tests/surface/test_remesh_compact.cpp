// RemeshComplex::compact (surface/remesh_complex.h): dropping the dead vertices and triangles
// keeps the live mesh, and every later operation does exactly what it would have done without it.
#include "surface/remesh_complex.h"
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

TEST(RemeshCompact, KeepsTheLiveMeshAndWhatLaterOperationsDo) {
  // Three tissues: junction curves, so curve vertices collapse and the curve edges are renumbered.
  const LabelImage img = three_boxes();
  const TriSurface input = extract(img, 3).surface;
  ASSERT_FALSE(input.junctions.empty());
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
  // Sweeps visit in index order and break ties by index: the renumbering must keep both. The
  // remesher's own sequence, compacting after every collapse sweep as it does.
  const std::size_t target = plain.vertices() - plain.vertices() / 5;
  for (RemeshComplex* m : {&plain, &compacted}) {
    const bool compacting = m == &compacted;
    for (int round = 0; round < 3; ++round) {
      for (int k = 0; k < 5; ++k) {
        const std::size_t n = m->collapse_short();
        if (compacting) m->compact();
        if (n == 0) break;
      }
      if (round >= 1) m->grade_stuck_edges(0.5);
      m->split_long();
      m->flip_all();
      m->relax();
    }
    ASSERT_TRUE(m->match_count(target));
    std::vector<int> moved;
    m->smooth_poor(M_PI / 6.0, moved);
    m->flip_around(moved);
  }
  EXPECT_EQ(plain.collapses, compacted.collapses);
  EXPECT_EQ(plain.splits, compacted.splits);
  EXPECT_EQ(plain.flips, compacted.flips);
  expect_same(plain.result(input), compacted.result(input));
}
