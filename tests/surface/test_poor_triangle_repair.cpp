// Repair of the triangles the polish leaves under 30 degrees (docs/surface-pipeline.md, "Repair
// and quality smoothing"): the repair kept only when it improves the Table 1 minima, its building
// blocks (capping the size around poor triangles, focused sweeps, removal of vertices of three
// triangles), its repeated attempts with a looser approximation bound, and the final quality
// smoothing.
#include "surface/remesh_complex.h"
#include "surface/surface_checks.h"
#include "surface/surface_distance.h"
#include "surface/surface_projection.h"
#include "surface/surface_quality.h"
#include "surface/surface_remesh.h"
#include "surface/triangle_geometry.h"
#include "support/coarse_phantom.h"
#include "support/surface_images.h"
#include "support/tolerances.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <vector>

using namespace tissuemesh;
using namespace tissuemesh::test;

namespace {

/// island_under_layer() coarsened by collapse sweeps alone at L = 3 voxels: a complex with
/// triangles under 30 degrees, for the repair's building blocks (capping, focusing).
struct CoarseIsland {
  LabelImage img = island_under_layer();
  TriSurface input = extract(img, 3).surface;
  SurfaceProjection on{input};
  RemeshComplex complex{input, on, options()};
  CoarseIsland() {
    complex.L = 3.0 * img.spacing.maxCoeff();
    for (int k = 0; k < 5 && complex.collapse_short() > 0; ++k) complex.compact();
  }
  RemeshOptions options() const {
    RemeshOptions o;
    o.max_deviation_mm = 0.5 * img.spacing.norm();
    return o;
  }
};

}  // namespace

TEST(SurfaceRemesh, RepairAroundPoorTrianglesIsKeptOnlyWhenItIsBetter) {
  // The island's small junction loops leave triangles under 30 degrees after the polish at these
  // budgets. Each result is compared with the same remeshing without the repair (the polished
  // surface): a kept repair is no worse in smallest angle and Q_min and better in one of them or
  // P30 (improves_table1_minima); a discarded one returns the polished surface bit for bit, with
  // its counters. Measured last: kept at 80, 110, 120 and 130; discarded at 100 (the repair's
  // smallest angle was lower: 19.02 against 19.03 degrees).
  const LabelImage img = island_under_layer();
  const TriSurface input = extract(img, 3).surface;
  const SurfaceProjection on_input(input);
  int kept = 0, discarded = 0;
  for (int budget : {80, 100, 110, 120, 130}) {
    RemeshOptions options;
    options.target_vertices = budget;
    options.max_deviation_mm = 0.5 * img.spacing.norm();
    Progress quiet;
    RemeshOptions without = options;
    without.repair = false;
    const RemeshResult polished = remesh_surface(input, on_input, without, quiet);
    const SurfaceQuality p = surface_quality(polished.surface);
    ASSERT_GT(p.p30_percent, 0.0) << "budget " << budget << ": nothing to repair";
    const RemeshResult r = remesh_surface(input, on_input, options, quiet);
    EXPECT_EQ(r.surface.points.size(), static_cast<std::size_t>(budget));
    EXPECT_TRUE(r.checks.valid()) << "budget " << budget;
    const SurfaceQuality q = surface_quality(r.surface);
    const bool same = r.surface.points == polished.surface.points && r.surface.triangles == polished.surface.triangles;
    if (same) {
      EXPECT_EQ(r.surface.labels, polished.surface.labels);
      EXPECT_EQ(r.surface.junctions, polished.surface.junctions);
      EXPECT_EQ(r.splits, polished.splits);
      EXPECT_EQ(r.collapses, polished.collapses);
      EXPECT_EQ(r.flips, polished.flips);
      EXPECT_EQ(r.angle_moves, polished.angle_moves);
      EXPECT_EQ(r.edge_length_mm, polished.edge_length_mm);
      ++discarded;
      continue;
    }
    EXPECT_TRUE(improves_table1_minima(p, q)) << "budget " << budget;
    EXPECT_GT(r.angle_moves, polished.angle_moves) << "budget " << budget << ": the repair's moves are counted";
    ++kept;
  }
  EXPECT_GE(kept, 1);
  EXPECT_GE(discarded, 1);
}

TEST(SurfaceQuality, ImprovementMeansNoWorseMinimaAndOneBetter) {
  SurfaceQuality before;
  before.min_angle_deg = 25.0;
  before.q_min = 0.45;
  before.p30_percent = 0.1;
  auto with = [&](double angle, double q, double p30) {
    SurfaceQuality s = before;
    s.min_angle_deg = angle, s.q_min = q, s.p30_percent = p30;
    return s;
  };
  EXPECT_TRUE(improves_table1_minima(before, with(26.0, 0.45, 0.1)));   // smallest angle better
  EXPECT_TRUE(improves_table1_minima(before, with(25.0, 0.46, 0.1)));   // Q_min better
  EXPECT_TRUE(improves_table1_minima(before, with(25.0, 0.45, 0.05)));  // only P30 better
  EXPECT_FALSE(improves_table1_minima(before, with(25.0, 0.45, 0.1)));  // the same
  EXPECT_FALSE(improves_table1_minima(before, with(30.0, 0.44, 0.0)));  // Q_min worse
  EXPECT_FALSE(improves_table1_minima(before, with(24.9, 0.60, 0.0)));  // smallest angle worse
  EXPECT_FALSE(improves_table1_minima(before, with(25.0, 0.45, 0.2)));  // only P30 worse
}

TEST(SurfaceRemesh, CappingPoorTrianglesRefinesAroundThem) {
  // RemeshComplex::cap_poor_triangles enters each triangle under the angle with its shortest
  // edge into the size cap: it reports those triangles, and the next split sweep then splits
  // edges there that it leaves alone without the cap.
  CoarseIsland island;
  const TriSurface& input = island.input;
  RemeshComplex& plain = island.complex;
  const double poor = M_PI / 6.0;
  std::size_t under = 0;
  const TriSurface coarse = plain.result(input);
  for (const auto& t : coarse.triangles)
    under += min_angle(coarse.points[t[0]], coarse.points[t[1]], coarse.points[t[2]]) < poor;
  ASSERT_GT(under, 0u);
  RemeshComplex capped = plain;
  EXPECT_EQ(capped.cap_poor_triangles(poor), under);
  EXPECT_GT(capped.split_long(), plain.split_long());
}

TEST(SurfaceRemesh, FocusedSweepsLeaveEverythingFarFromPoorTrianglesAlone) {
  // focus_on_poor_triangles limits the sweeps to within a radius of the poor triangles (the
  // repair's reach): a relaxation pass then moves no vertex farther than that from every poor
  // triangle's centroid, while it moves some near them, and without the focus it moves far ones too.
  CoarseIsland island;
  const TriSurface& input = island.input;
  RemeshComplex& plain = island.complex;
  const double poor = M_PI / 6.0, radius = 1.5 * plain.L;
  const TriSurface before = plain.result(input);
  std::vector<Eigen::Vector3d> centres;
  for (const auto& t : before.triangles) {
    const auto& p = before.points;
    if (min_angle(p[t[0]], p[t[1]], p[t[2]]) < poor) centres.push_back((p[t[0]] + p[t[1]] + p[t[2]]) / 3.0);
  }
  ASSERT_FALSE(centres.empty());
  auto near = [&](const Eigen::Vector3d& x) {
    for (const auto& c : centres)
      if ((x - c).norm() <= radius) return true;
    return false;
  };
  auto moved = [&](RemeshComplex c, bool far_ones) {  // relaxes a copy; counts moved near / far vertices
    c.relax();
    const TriSurface after = c.result(input);
    EXPECT_EQ(after.points.size(), before.points.size());  // relaxation only moves vertices
    std::size_t n = 0;
    for (std::size_t v = 0; v < before.points.size(); ++v)
      n += after.points[v] != before.points[v] && near(before.points[v]) != far_ones;
    return n;
  };
  RemeshComplex focused = plain;
  focused.focus_on_poor_triangles(poor, radius);
  EXPECT_EQ(moved(focused, true), 0u);
  EXPECT_GT(moved(focused, false), 0u);
  EXPECT_GT(moved(plain, true), 0u);
}

TEST(SurfaceRemesh, QualitySmoothingKeepsTheAnglesWhileItRaisesQuality) {
  // RemeshComplex::smooth_low_quality moves the surface vertices of triangles under a quality to
  // raise the smallest quality around each, keeping the vertex's smallest angle at least min(its
  // own, 30 degrees) and its count of angles under 30 degrees from growing. Every vertex it
  // reports has moved, and pass after pass (same triangles, only moves) the surface's Q_min never
  // drops, P30 never grows and the smallest angle never drops below min(its value, 30 degrees).
  // The small test images never need it; a coarse phantom, remeshed at two edge lengths and
  // polished, does. Mutation checks (measured when written): without the angle floor the
  // smallest angle drops at L = 5 mm (17.51 -> 15.74 degrees); without the count of angles under
  // 30 degrees P30 grows at L = 8 mm (0.6903 -> 0.7125 %); the floor and the count each hold
  // alone at the other length; accepting a move that does not raise the quality (>= instead of
  // >) reports vertices that did not move. (A wrong objective is caught by the next test.)
  const CoarsePhantom& phantom = coarse_phantom();
  const TriSurface& input = phantom.surface;
  const SurfaceProjection& on = phantom.on_surface;
  const double poor = M_PI / 6.0;
  const double below = 0.7;  // far above the polish's Q_min: most vertices are candidates
  for (double L : {5.0, 8.0}) {
    RemeshOptions options;
    options.max_deviation_mm = phantom.max_deviation_mm;
    RemeshComplex c(input, on, options);
    c.L = L;
    for (int round = 0; round < 3; ++round) {
      for (int k = 0; k < 20 && c.collapse_short() > 0; ++k) c.compact();
      c.split_long();
      c.flip_all();
      c.relax();
    }
    for (int pass = 0; pass < 40; ++pass) {  // the angle smoothing first, as in remesh_surface
      std::vector<int> moved;
      c.smooth_poor(poor, moved);
      if (moved.empty()) break;
      c.flip_around(moved);
    }
    const SurfaceQuality start = surface_quality(c.result(input));
    SurfaceQuality q = start;
    std::size_t moves = 0;
    for (int pass = 0; pass < 20; ++pass) {
      // No vertex dies here (the last sweeps compacted, splits only add), so result() keeps the
      // complex's vertex numbering.
      const std::vector<Eigen::Vector3d> at = c.result(input).points;
      std::vector<int> moved;
      c.smooth_low_quality(below, poor, moved);
      if (moved.empty()) break;
      moves += moved.size();
      const TriSurface now = c.result(input);
      ASSERT_EQ(now.points.size(), at.size());
      for (int v : moved) EXPECT_NE(now.points[static_cast<std::size_t>(v)], at[static_cast<std::size_t>(v)]) << "vertex " << v;
      const SurfaceQuality next = surface_quality(now);
      EXPECT_GE(next.q_min, q.q_min) << "L " << L << " pass " << pass;
      EXPECT_GE(std::min(next.min_angle_deg, 30.0), std::min(q.min_angle_deg, 30.0)) << "L " << L << " pass " << pass;
      EXPECT_LE(next.p30_percent, q.p30_percent) << "L " << L << " pass " << pass;
      q = next;
    }
    EXPECT_GT(moves, 0u) << "L " << L;
    EXPECT_TRUE(check_surface(c.result(input)).valid()) << "L " << L;
  }
}

TEST(SurfaceRemesh, FinalQualitySmoothingRaisesTheWorstTriangle) {
  // When the remeshed surface's Q_min is under kQualitySmoothingBelow (the paper's 2.1K Q_min,
  // 0.486), remesh_surface ends
  // with the quality smoothing and says so in a progress note: "Q_min A -> B, N moves". On the
  // coarse phantom at budget 1,900 (measured when written: 0.3947 -> 0.4573, 4 moves; the budget
  // moves with the remesher's sequence of operations: 1,500 before the sweeps were split in two
  // halves, 1,250 before the grid projection; budgets 1,000-2,000 by 50 now raise Q_min at
  // 1,900 and 1,950 only) the note's B is the result's Q_min and above A. Mutation check (no
  // final smoothing): no such note.
  const CoarsePhantom& phantom = coarse_phantom();
  std::string note;
  Progress progress([&](Progress::Event e, const std::string&, const std::string& text, double, double) {
    if (e == Progress::Event::Note && text.rfind("quality smoothing", 0) == 0) note = text;
  });
  RemeshOptions options;
  options.target_vertices = 1900;
  options.max_deviation_mm = phantom.max_deviation_mm;
  const RemeshResult r = remesh_surface(phantom.surface, phantom.on_surface, options, progress);
  ASSERT_FALSE(note.empty());
  double before = 0.0, after = 0.0;
  ASSERT_EQ(std::sscanf(note.c_str() + note.find("Q_min "), "Q_min %lf -> %lf", &before, &after), 2) << note;
  EXPECT_LT(before, kQualitySmoothingBelow) << note;
  EXPECT_GT(after, before) << note;
  EXPECT_NEAR(surface_quality(r.surface).q_min, after, kPrintedFourDecimals) << note;
  EXPECT_GT(r.quality_moves, 0u);
  EXPECT_TRUE(r.checks.valid());
}

TEST(SurfaceRemesh, CollapsePoorRemovesAVertexOfThreeTriangles) {
  // A regular octahedron (one tissue) with one face split at its centroid: the new vertex has
  // three triangles of angles 30, 30, 120 degrees, and no position in the face does better than
  // 30. collapse_poor removes it: the face is whole again (60 degrees). Mutation check (only
  // vertices of two triangles removed): the vertex stays, the smallest angle stays 30.
  TriSurface s;
  s.tissue_names = {"a"};
  s.points = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  const std::vector<std::array<int, 3>> outward{{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4},
                                                {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
  for (auto t : outward) {
    std::swap(t[1], t[2]);  // stored from the outside (0) into the tissue (1)
    s.triangles.push_back(t);
    s.labels.push_back({0, 1});
  }
  s.points.push_back((s.points[0] + s.points[4] + s.points[2]) / 3.0);  // centroid of the first face
  const std::array<int, 3> first = s.triangles[0];
  s.triangles[0] = {first[0], first[1], 6};
  s.triangles.push_back({first[1], first[2], 6});
  s.triangles.push_back({first[2], first[0], 6});
  s.labels.resize(s.triangles.size(), {0, 1});
  ASSERT_TRUE(check_surface(s).valid());
  const SurfaceProjection on(s);
  RemeshOptions options;
  options.max_deviation_mm = 0.01;
  RemeshComplex c(s, on, options);
  c.L = 1.0;
  const double poor = 31.0 * M_PI / 180.0;
  EXPECT_NEAR(surface_quality(c.result(s)).min_angle_deg, 30.0, kAngleDeg);
  EXPECT_EQ(c.collapse_poor(poor), 1u);
  EXPECT_EQ(c.vertices(), 6u);
  const TriSurface after = c.result(s);
  EXPECT_TRUE(check_surface(after).valid());
  EXPECT_NEAR(surface_quality(after).min_angle_deg, 60.0, kAngleDeg);
  EXPECT_EQ(c.collapse_poor(poor), 0u);  // nothing poor left
}

TEST(SurfaceRemesh, RepeatedRepairWithALooserBoundWidensTrianglesOnFoldsNearTheEdgeLength) {
  // Layers folding with a period of 3 voxels, remeshed at L = 3.5 mm: vertices held within L/4 of
  // every fold leave triangles under 26.5 degrees after one repair attempt; the later attempts,
  // with the bound 1.5 times looser each, may cut across folds the edges cannot resolve. Measured
  // when written: one attempt 20.66 deg, Q_min 0.318, P30 0.090 %, Hausdorff 1.66 mm; the default
  // 28.21 deg, 0.466, 0.004 %, 1.58 mm (its second attempt kept, the loop then stops above 26.5).
  const LabelImage img = folds_every_three_voxels();
  const TriSurface input = extract(img, 7).surface;
  const SurfaceProjection on_input(input);
  RemeshOptions options;
  options.target_vertices = 4000;
  options.max_deviation_mm = 0.5 * img.spacing.norm();
  Progress quiet;
  RemeshOptions once = options;
  once.repair_attempts = 1;
  const SurfaceQuality one = surface_quality(remesh_surface(input, on_input, once, quiet).surface);
  ASSERT_LT(one.min_angle_deg, 26.5) << "one attempt already meets the seed paper's smallest angle: nothing to test";

  const RemeshResult r = remesh_surface(input, on_input, options, quiet);
  EXPECT_EQ(r.surface.points.size(), 4000u);
  EXPECT_TRUE(r.checks.valid());
  const SurfaceQuality q = surface_quality(r.surface);
  EXPECT_TRUE(improves_table1_minima(one, q)) << q.min_angle_deg << " deg, Q_min " << q.q_min;
  EXPECT_GE(q.min_angle_deg, 26.5);
  // The loosest attempt's bound, L/4 times 1.5^3, holds both ways (input vertices to the
  // triangles around them, changed triangles to their patch).
  const SurfaceProjection on_remeshed(r.surface);
  const double bound = 0.25 * std::pow(1.5, 3) * r.edge_length_mm;
  EXPECT_LE(hausdorff_distance(r.surface, on_remeshed, input, on_input).symmetric_mm(), bound);

  RemeshOptions none = options;
  none.repair_attempts = 0;
  EXPECT_THROW(remesh_surface(input, on_input, none, quiet), std::invalid_argument);
}
