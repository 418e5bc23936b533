// The surface checks themselves (the surface pipeline's validity instruments): each defect they
// name, built by hand on tetrahedra, is found and counted, and a sound surface passes with its
// exact volume; the re-check after moving points agrees with a full check.
#include "surface/surface_checks.h"
#include "support/surface_images.h"
#include "support/surface_reports.h"
#include "support/tolerances.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <random>
#include <stdexcept>
#include <string>

using namespace tissuemesh;
using namespace tissuemesh::test;

namespace {

/// Adds the boundary of the tetrahedron on s.points[v[0..3]] as tissue `id` against the outside:
/// its outward faces, stored reversed with labels {0, id} (the TriSurface convention: the normal
/// points from the outside into the tissue).
void add_tetrahedron(TriSurface& s, const std::array<int, 4>& v, int id) {
  const auto& p = s.points;
  const double orientation = (p[v[1]] - p[v[0]]).dot((p[v[2]] - p[v[0]]).cross(p[v[3]] - p[v[0]]));
  // Outward faces of a positively oriented tetrahedron (0, 1, 2, 3).
  std::array<std::array<int, 3>, 4> faces{{{v[0], v[2], v[1]}, {v[0], v[1], v[3]}, {v[0], v[3], v[2]}, {v[1], v[2], v[3]}}};
  for (auto& f : faces) {
    if (orientation < 0.0) std::swap(f[1], f[2]);
    std::swap(f[1], f[2]);  // stored inward: from the outside (0) into the tissue
    s.triangles.push_back(f);
    s.labels.push_back({0, id});
  }
}

/// One tissue: the unit corner tetrahedron (0,0,0), (1,0,0), (0,1,0), (0,0,1), volume 1/6 mm^3.
TriSurface corner_tetrahedron() {
  TriSurface s;
  s.tissue_names = {"a"};
  s.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  add_tetrahedron(s, {0, 1, 2, 3}, 1);
  return s;
}

}  // namespace

TEST(SurfaceChecks, ClosedTetrahedronPassesWithItsExactVolume) {
  const SurfaceCheckReport r = check_surface(corner_tetrahedron());
  ASSERT_EQ(r.tissues.size(), 1u);
  const TissueSurfaceCheck& t = r.tissues[0];
  EXPECT_TRUE(r.valid());
  EXPECT_TRUE(t.closed_and_oriented());
  EXPECT_EQ(t.nonmanifold_vertices, 0u);
  EXPECT_EQ(t.intersecting_pairs, 0);
  EXPECT_EQ(t.vertices, 4u);
  EXPECT_EQ(t.triangles, 4u);
  // Divergence theorem on exact small coordinates: round-off only.
  EXPECT_NEAR(t.volume_mm3, 1.0 / 6.0, kRelativeRoundoff / 6.0);
}

TEST(SurfaceChecks, MissingTriangleLeavesThreeOpenEdges) {
  TriSurface s = corner_tetrahedron();
  s.triangles.pop_back();
  s.labels.pop_back();
  const SurfaceCheckReport r = check_surface(s);
  EXPECT_EQ(r.tissues[0].open_edges, 3u);
  EXPECT_EQ(r.tissues[0].intersecting_pairs, -1);  // not checked on an open boundary
  EXPECT_FALSE(r.valid());
}

TEST(SurfaceChecks, ReversedTriangleMisorientsItsThreeEdges) {
  TriSurface s = corner_tetrahedron();
  std::swap(s.triangles[0][1], s.triangles[0][2]);
  const SurfaceCheckReport r = check_surface(s);
  EXPECT_EQ(r.tissues[0].misoriented_edges, 3u);
  EXPECT_EQ(r.tissues[0].open_edges, 0u);
  EXPECT_FALSE(r.valid());
}

TEST(SurfaceChecks, TetrahedraTouchingAtOneVertexAreNotManifoldThere) {
  // Two tetrahedra of one tissue, point-reflected through the shared vertex 0: every edge is used
  // twice in opposite directions, but vertex 0 has two fans.
  TriSurface s = corner_tetrahedron();
  s.points.insert(s.points.end(), {{-1, 0, 0}, {0, -1, 0}, {0, 0, -1}});
  add_tetrahedron(s, {0, 4, 5, 6}, 1);
  const SurfaceCheckReport r = check_surface(s);
  const TissueSurfaceCheck& t = r.tissues[0];
  EXPECT_TRUE(t.closed_and_oriented());
  EXPECT_EQ(t.nonmanifold_vertices, 1u);
  EXPECT_EQ(t.intersecting_pairs, -1);
  EXPECT_FALSE(r.valid());
  // Apart from the touching vertex the two are sound: the volume is both tetrahedra's.
  EXPECT_NEAR(t.volume_mm3, 2.0 / 6.0, kRelativeRoundoff);
}

TEST(SurfaceChecks, InterpenetratingTetrahedraIntersect) {
  TriSurface s = corner_tetrahedron();
  for (int k = 0; k < 4; ++k) s.points.push_back(s.points[static_cast<std::size_t>(k)] + Eigen::Vector3d(0.2, 0.2, 0.2));
  add_tetrahedron(s, {4, 5, 6, 7}, 1);
  const SurfaceCheckReport r = check_surface(s);
  EXPECT_EQ(r.tissues[0].nonmanifold_vertices, 0u);
  EXPECT_GT(r.tissues[0].intersecting_pairs, 0);
  EXPECT_FALSE(r.valid());
}

TEST(SurfaceChecks, CollinearTriangleIsReportedAsIntersectingItself) {
  // The apex moved onto the midpoint of edge 0-1: triangle (0, 1, 3) is a segment.
  TriSurface s = corner_tetrahedron();
  s.points[3] = {0.5, 0.0, 0.0};
  std::vector<int> bad;
  const SurfaceCheckReport r = check_surface(s, &bad);
  EXPECT_GT(r.tissues[0].intersecting_pairs, 0);
  EXPECT_FALSE(r.valid());
  int collinear = -1;
  for (std::size_t t = 0; t < s.triangles.size(); ++t) {
    auto v = s.triangles[t];
    std::sort(v.begin(), v.end());
    if (v == std::array<int, 3>{0, 1, 3}) collinear = static_cast<int>(t);
  }
  ASSERT_GE(collinear, 0);
  EXPECT_TRUE(std::binary_search(bad.begin(), bad.end(), collinear));
}

TEST(SurfaceChecks, TriangleStoredTwiceAndJunctionOffTheTrianglesAreCounted) {
  TriSurface s = corner_tetrahedron();
  s.triangles.push_back({s.triangles[0][1], s.triangles[0][2], s.triangles[0][0]});  // same vertices, rotated
  s.labels.push_back({0, 1});
  EXPECT_EQ(check_surface(s).duplicate_triangles, 1u);

  TriSurface j = corner_tetrahedron();
  j.junctions = {{0, 1}};  // an edge where only two triangles meet
  const SurfaceCheckReport r = check_surface(j);
  EXPECT_EQ(r.junction_edges, 1u);
  EXPECT_EQ(r.junction_edges_off_junction, 1u);
  EXPECT_FALSE(r.valid());
}

TEST(SurfaceChecks, RecheckAfterMovesAgreesWithAFullCheck) {
  // Three tissues with a triple junction, every vertex pushed up to 1.2 voxels in a random
  // direction: many folds and interpenetrations. Then, as the extraction's unfolding does, the
  // vertices of the intersecting triangles move halfway back, round after round, and each
  // round's re-check must equal a full check of the same points: the intersecting triangles, and
  // per tissue the pair count and the volume (bit for bit: the same sums in the same order).
  TriSurface s = extract(three_boxes(), 3).surface;
  const std::vector<Eigen::Vector3d> original = s.points;
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> offset(-1.2, 1.2);
  for (auto& p : s.points) p += Eigen::Vector3d(offset(rng), offset(rng), offset(rng));
  std::vector<int> bad;
  SurfaceCheckReport report = check_surface(s, &bad);
  ASSERT_FALSE(bad.empty());
  int rounds_with_pairs = 0;
  for (int round = 0; round < 12 && !bad.empty(); ++round) {
    std::vector<int> moved;
    for (int t : bad)
      for (int v : s.triangles[static_cast<std::size_t>(t)]) moved.push_back(v);
    std::sort(moved.begin(), moved.end());
    moved.erase(std::unique(moved.begin(), moved.end()), moved.end());
    for (int v : moved) s.points[static_cast<std::size_t>(v)] = 0.5 * (s.points[static_cast<std::size_t>(v)] + original[static_cast<std::size_t>(v)]);
    std::vector<int> again, full_bad;
    const SurfaceCheckReport recheck = recheck_after_moves(s, report, bad, moved, &again);
    const SurfaceCheckReport full = check_surface(s, &full_bad);
    EXPECT_EQ(again, full_bad) << "round " << round;
    ASSERT_EQ(recheck.tissues.size(), full.tissues.size());
    expect_same_report(recheck, full, "round " + std::to_string(round));
    rounds_with_pairs += !again.empty();
    report = recheck;
    bad = again;
  }
  EXPECT_TRUE(bad.empty());          // back at the extraction, which has no intersections
  EXPECT_GE(rounds_with_pairs, 2);   // the comparison covered re-checks that found pairs
}

TEST(SurfaceChecks, RecheckRefusesAnIntersectingTriangleThatDidNotMove) {
  TriSurface s = corner_tetrahedron();
  s.points[3] = {0.5, 0.0, 0.0};  // a collinear triangle: intersecting itself
  std::vector<int> bad;
  const SurfaceCheckReport r = check_surface(s, &bad);
  ASSERT_FALSE(bad.empty());
  EXPECT_THROW(recheck_after_moves(s, r, bad, {}), std::invalid_argument);
}

TEST(SurfaceChecks, RecheckFindsATriangleMadeCollinear) {
  // A sound tetrahedron, then its apex moved onto the midpoint of edge 0-1: the re-check around
  // the moved vertex reports what a full check does (CGAL's rule: the pair (f, f)).
  TriSurface s = corner_tetrahedron();
  const SurfaceCheckReport sound = check_surface(s);
  ASSERT_TRUE(sound.valid());
  s.points[3] = {0.5, 0.0, 0.0};
  std::vector<int> again, full_bad;
  const SurfaceCheckReport recheck = recheck_after_moves(s, sound, {}, {3}, &again);
  const SurfaceCheckReport full = check_surface(s, &full_bad);
  EXPECT_GT(full.tissues[0].intersecting_pairs, 0);
  EXPECT_EQ(recheck.tissues[0].intersecting_pairs, full.tissues[0].intersecting_pairs);
  EXPECT_EQ(again, full_bad);
  EXPECT_FALSE(recheck.valid());
}

TEST(SurfaceChecks, RecheckLeavesAnUncheckedTissueUncheckedWithItsNewVolume) {
  // An open tissue (a triangle missing) is not tested for intersections (-1); after a move its
  // volume still follows, as in a full check.
  TriSurface s = corner_tetrahedron();
  s.triangles.erase(s.triangles.begin());  // the face in z = 0: the others' volume terms then
  s.labels.erase(s.labels.begin());        // depend on the moved apex
  const SurfaceCheckReport before = check_surface(s);
  ASSERT_EQ(before.tissues[0].intersecting_pairs, -1);
  s.points[3] = {0.1, 0.1, 2.0};
  std::vector<int> again, full_bad;
  const SurfaceCheckReport recheck = recheck_after_moves(s, before, {}, {3}, &again);
  const SurfaceCheckReport full = check_surface(s, &full_bad);
  expect_same_report(recheck, full, "open tissue");
  EXPECT_NE(recheck.tissues[0].volume_mm3, before.tissues[0].volume_mm3);
  EXPECT_EQ(again, full_bad);
}

TEST(SurfaceChecks, GridPairSearchFindsExactlyWhatCgalFinds) {
  // The extraction's fast search (PairSearch::Grid) against CGAL's self_intersections per tissue:
  // three tissues with a triple junction, every vertex pushed by up to 0.3, 0.6 and 1.2 voxels in
  // a random direction (a few, then many folds and interpenetrations, across interfaces too), and
  // the hand-made defects: a collinear triangle, an open tissue (not checked: -1 either way).
  const TriSurface extracted = extract(three_boxes(), 3).surface;
  std::vector<TriSurface> cases;
  for (double amplitude : {0.3, 0.6, 1.2}) {
    TriSurface s = extracted;
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> offset(-amplitude, amplitude);
    for (auto& p : s.points) p += Eigen::Vector3d(offset(rng), offset(rng), offset(rng));
    cases.push_back(s);
  }
  // The most folded case with one outer triangle of tissue 1 gone: tissue 1 is open (not
  // checked), the others are, and their interfaces with tissue 1 count only for them.
  cases.push_back(cases.back());
  for (std::size_t t = 0; t < cases.back().triangles.size(); ++t)
    if (cases.back().labels[t] == std::array<int, 2>{0, 1}) {
      cases.back().triangles.erase(cases.back().triangles.begin() + static_cast<std::ptrdiff_t>(t));
      cases.back().labels.erase(cases.back().labels.begin() + static_cast<std::ptrdiff_t>(t));
      break;
    }
  cases.push_back(corner_tetrahedron());
  cases.back().points[3] = {0.5, 0.0, 0.0};
  cases.push_back(corner_tetrahedron());
  cases.back().triangles.pop_back();
  cases.back().labels.pop_back();
  long long pairs_in_every_tissue_case = 0;
  for (std::size_t k = 0; k < cases.size(); ++k) {
    std::vector<int> by_cgal, by_grid;
    const SurfaceCheckReport cgal = check_surface(cases[k], &by_cgal, PairSearch::Cgal);
    const SurfaceCheckReport grid = check_surface(cases[k], &by_grid, PairSearch::Grid);
    expect_same_report(grid, cgal, "case " + std::to_string(k));
    EXPECT_EQ(by_grid, by_cgal) << "case " << k;
    bool every_tissue = true;
    for (const auto& t : cgal.tissues) every_tissue = every_tissue && t.intersecting_pairs > 0;
    pairs_in_every_tissue_case += every_tissue;
  }
  EXPECT_GE(pairs_in_every_tissue_case, 2);  // the comparison covered pairs in each of the three tissues
  const SurfaceCheckReport mixed = check_surface(cases[3], nullptr, PairSearch::Grid);
  EXPECT_EQ(mixed.tissues[0].intersecting_pairs, -1);  // ... and an unchecked tissue beside checked ones
  EXPECT_GT(mixed.tissues[1].intersecting_pairs + mixed.tissues[2].intersecting_pairs, 0);
}
