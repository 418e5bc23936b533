// Controlled-resolution remeshing of the multi-material surface (docs/surface-pipeline.md,
// "Remeshing to a vertex budget"): budget, closedness, shared interfaces, junction preservation,
// distance to the input, determinism.
#include "core/errors.h"
#include "image/folded_layers.h"
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
#include <cstdio>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

using namespace tissuemesh;
using namespace tissuemesh::test;

namespace {

RemeshResult remesh(const TriSurface& s, const SurfaceProjection& on, int budget, double voxel_diagonal) {
  RemeshOptions options;
  options.target_vertices = budget;
  options.max_deviation_mm = 0.5 * voxel_diagonal;
  Progress progress;
  return remesh_surface(s, on, options, progress);
}

std::set<std::array<int, 2>> pairs(const TriSurface& s) { return {s.labels.begin(), s.labels.end()}; }

/// The smallest triangle angle (degrees) of a remeshed surface and its triangles under 30 degrees.
struct AngleStats {
  double smallest = 180.0;
  std::size_t under_30 = 0;
};

/// Remeshes `input` to `budget`, checks budget and validity, and returns its angle statistics.
AngleStats remeshed_angles(const TriSurface& input, const SurfaceProjection& on, int budget, double voxel_diagonal) {
  const RemeshResult r = remesh(input, on, budget, voxel_diagonal);
  EXPECT_EQ(r.surface.points.size(), static_cast<std::size_t>(budget));
  EXPECT_TRUE(r.checks.valid()) << "budget " << budget;
  AngleStats a;
  for (const auto& t : r.surface.triangles) {
    const auto& p = r.surface.points;
    const double angle = min_angle(p[t[0]], p[t[1]], p[t[2]]) * 180.0 / M_PI;
    a.smallest = std::min(a.smallest, angle);
    a.under_30 += angle < 30.0;
  }
  return a;
}

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

TEST(SurfaceRemesh, NestedSpheresMeetTheBudgetClosedAndCloseToTheInput) {
  const LabelImage img = nested_spheres();
  const TriSurface input = extract(img, 2).surface;
  const SurfaceProjection on_input(input);
  const double diagonal = img.spacing.norm();
  const RemeshResult r = remesh(input, on_input, 300, diagonal);
  EXPECT_EQ(r.surface.points.size(), 300u);
  EXPECT_LT(r.surface.points.size(), input.points.size() / 3);  // a real coarsening
  ASSERT_NO_THROW(r.surface.validate("remeshed spheres"));
  const SurfaceCheckReport checks = check_surface(r.surface);
  EXPECT_TRUE(checks.valid());
  for (const auto& t : checks.tissues) EXPECT_EQ(t.intersecting_pairs, 0) << t.name;
  EXPECT_EQ(pairs(r.surface), pairs(input));  // 0|1 and 1|2, each stored once
  const SurfaceProjection on_remeshed(r.surface);
  const SurfaceDistance d = hausdorff_distance(r.surface, on_remeshed, input, on_input);
  EXPECT_LE(d.symmetric_mm(), kRemeshHausdorffVoxelDiagonals * diagonal);
}

TEST(SurfaceRemesh, ReportsEveryRoundAndTheBudgetAsProgressNotes) {
  // A long stage shows where it is: one note per round with the vertex count and the edge length
  // L (mm) it worked at, then one when the budget is met (and one for a repair, if one is tried).
  const LabelImage img = nested_spheres();
  const TriSurface input = extract(img, 2).surface;
  const SurfaceProjection on_input(input);
  std::vector<std::string> notes;
  Progress progress([&](Progress::Event e, const std::string& stage, const std::string& text, double, double) {
    if (e == Progress::Event::Note && stage == "surface remeshing") notes.push_back(text);
  });
  RemeshOptions options;
  options.target_vertices = 300;
  options.iterations = 4;
  remesh_surface(input, on_input, options, progress);
  ASSERT_GE(notes.size(), 5u);
  ASSERT_LE(notes.size(), 6u);
  for (int k = 0; k < 4; ++k) {
    EXPECT_EQ(notes[k].rfind("round " + std::to_string(k + 1) + "/4: ", 0), 0u) << notes[k];
    EXPECT_NE(notes[k].find(" mm"), std::string::npos) << notes[k];
  }
  EXPECT_EQ(notes[4].rfind("budget met (300 vertices)", 0), 0u) << notes[4];
  if (notes.size() == 6) {  // only when the polish left a triangle under 30 degrees
    EXPECT_EQ(notes[5].rfind("repair around ", 0), 0u) << notes[5];
  }
}

TEST(SurfaceRemesh, ThinShellStaysIntersectionFreeAtCoarseBudgets) {
  // The shell's two sides are 1 mm apart and the edges at these budgets 3-10 mm long. Without the
  // intersection guard (mutation check) the two sides cut through each other at budget 20.
  const LabelImage img = thin_shell();
  const TriSurface input = extract(img, 2).surface;
  const SurfaceProjection on_input(input);
  for (int budget : {20, 40, 100}) {
    const RemeshResult r = remesh(input, on_input, budget, img.spacing.norm());
    EXPECT_EQ(r.surface.points.size(), static_cast<std::size_t>(budget));
    const SurfaceCheckReport checks = check_surface(r.surface);
    EXPECT_TRUE(checks.valid()) << "budget " << budget;
    for (const auto& t : checks.tissues) EXPECT_EQ(t.intersecting_pairs, 0) << t.name << ", budget " << budget;
    EXPECT_EQ(pairs(r.surface), pairs(input));
  }
}

TEST(SurfaceRemesh, JunctionPolylinesSurviveOnTheInputJunctions) {
  const LabelImage img = three_boxes();
  const SurfaceExtraction ex = extract(img, 3);
  const TriSurface& input = ex.surface;
  const SurfaceProjection on_input(input);
  const RemeshResult r = remesh(input, on_input, 400, img.spacing.norm());
  EXPECT_EQ(r.surface.points.size(), 400u);
  EXPECT_TRUE(check_surface(r.surface).valid());
  EXPECT_EQ(pairs(r.surface), pairs(input));
  // The same curves, each still one polyline (closed ones closed), every vertex on its input curve.
  ASSERT_EQ(r.surface.junctions.size(), input.junctions.size());
  for (std::size_t c = 0; c < input.junctions.size(); ++c) {
    const auto& in = input.junctions[c];
    const auto& out = r.surface.junctions[c];
    ASSERT_GE(out.size(), 2u);
    EXPECT_EQ(in.front() == in.back(), out.front() == out.back()) << "curve " << c;
    for (int v : out)
      EXPECT_LE((on_input.onto_curve(static_cast<int>(c), r.surface.points[v]) - r.surface.points[v]).norm(),
                kConstrainedCoordinateMm)
          << "curve " << c << " vertex " << v;
  }
  // Corners (where curves meet) are kept where they were.
  std::set<std::array<double, 3>> in_ends, out_ends;
  for (const auto& l : input.junctions)
    if (l.front() != l.back())
      for (int v : {l.front(), l.back()}) in_ends.insert({input.points[v][0], input.points[v][1], input.points[v][2]});
  for (const auto& l : r.surface.junctions)
    if (l.front() != l.back())
      for (int v : {l.front(), l.back()})
        out_ends.insert({r.surface.points[v][0], r.surface.points[v][1], r.surface.points[v][2]});
  EXPECT_EQ(in_ends, out_ends);
  // The flat 1|2 interface stays in its plane x = x0.
  const double x0 = img.origin[0] + 14.5;
  for (std::size_t t = 0; t < r.surface.triangles.size(); ++t) {
    if (r.surface.labels[t] != std::array<int, 2>{1, 2}) continue;
    for (int v : r.surface.triangles[t]) EXPECT_NEAR(r.surface.points[v][0], x0, kConstrainedCoordinateMm);
  }
}

TEST(SurfaceRemesh, IsDeterministic) {
  const LabelImage img = three_boxes();
  const TriSurface input = extract(img, 3).surface;
  const SurfaceProjection on_input(input);
  const RemeshResult a = remesh(input, on_input, 400, img.spacing.norm());
  const RemeshResult b = remesh(input, on_input, 400, img.spacing.norm());
  EXPECT_EQ(a.surface.triangles, b.surface.triangles);
  EXPECT_EQ(a.surface.labels, b.surface.labels);
  EXPECT_EQ(a.surface.junctions, b.surface.junctions);
  EXPECT_EQ(a.surface.points, b.surface.points);
}

TEST(SurfaceRemesh, TwoThreadsGiveTheSameSurfaceAsOne) {
  // The coarse phantom's extraction has more vertices than the partitioned sweeps' threshold
  // (10,000, surface/remesh_partition.cpp), so its first rounds' collapse and relaxation sweeps run
  // as two halves; on one thread the halves run one after the other.
  const CoarsePhantom& phantom = coarse_phantom();
  ASSERT_GT(phantom.surface.points.size(), 10000u);
  RemeshOptions options;
  options.target_vertices = 1500;
  options.max_deviation_mm = phantom.max_deviation_mm;
  Progress progress;
  options.threads = 1;
  const RemeshResult one = remesh_surface(phantom.surface, phantom.on_surface, options, progress);
  options.threads = 2;
  const RemeshResult two = remesh_surface(phantom.surface, phantom.on_surface, options, progress);
  EXPECT_GT(two.partitioned_sweeps, 0u);
  EXPECT_EQ(one.partitioned_sweeps, two.partitioned_sweeps);
  EXPECT_EQ(one.collapses, two.collapses);
  EXPECT_EQ(one.surface.points, two.surface.points);
  EXPECT_EQ(one.surface.triangles, two.surface.triangles);
  EXPECT_EQ(one.surface.labels, two.surface.labels);
  EXPECT_EQ(one.surface.junctions, two.surface.junctions);
  EXPECT_TRUE(two.checks.valid());
}

TEST(SurfaceRemesh, RefusesABudgetItCannotMeetNamingTheKeyAndACount) {
  // Budget 1: below the junction corners, refused before any work; budget 3: above them, but no
  // remeshing keeps three boxes' surfaces closed with so few vertices.
  const LabelImage img = three_boxes();
  const TriSurface input = extract(img, 3).surface;
  const SurfaceProjection on_input(input);
  auto message_of = [&](int budget) {
    try {
      remesh(input, on_input, budget, img.spacing.norm());
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no InputError");
  };
  const std::string below = message_of(1);
  EXPECT_EQ(below.rfind("surface.target_vertices: 1 vertices cannot be met on this surface; it must keep ", 0), 0u) << below;
  EXPECT_NE(below.find("junction corners"), std::string::npos) << below;
  const std::string stalled = message_of(3);
  EXPECT_EQ(stalled.rfind("surface.target_vertices: 3 vertices cannot be met on this surface; ", 0), 0u) << stalled;
  int at_least = 0;
  const auto at = stalled.find("Raise the budget to at least ");
  ASSERT_NE(at, std::string::npos) << stalled;
  at_least = std::atoi(stalled.c_str() + at + 29);
  EXPECT_GT(at_least, 3) << stalled;
  RemeshOptions none;
  Progress progress;
  EXPECT_THROW(remesh_surface(input, on_input, none, progress), InputError);
}

TEST(SurfaceRemesh, TrianglesAroundASmallJunctionLoopAreGradedNotSlivers) {
  // The island's junction loops are ~2 mm around, its corners fixed, the edges at these budgets
  // 4.5-6.5 mm: without the size cap around stuck junction edges (surface/graded_size_cap.h;
  // mutation check) the triangles touching the loops reach 11.2 degrees.
  const LabelImage img = island_under_layer();
  const TriSurface input = extract(img, 3).surface;
  const SurfaceProjection on_input(input);
  const Eigen::Vector3d contact = img.origin + Eigen::Vector3d(14.5, 14.5, 12.5);  // top of the island
  for (int budget : {100, 120, 150}) {
    const RemeshResult r = remesh(input, on_input, budget, img.spacing.norm());
    EXPECT_EQ(r.surface.points.size(), static_cast<std::size_t>(budget));
    EXPECT_TRUE(r.checks.valid()) << "budget " << budget;
    double smallest = 180.0;
    for (const auto& t : r.surface.triangles) {
      bool near = false;
      for (int v : t) near = near || (r.surface.points[v] - contact).norm() < 2.0;
      const auto& p = r.surface.points;
      if (near) smallest = std::min(smallest, min_angle(p[t[0]], p[t[1]], p[t[2]]) * 180.0 / M_PI);
    }
    EXPECT_GT(smallest, kGradedLoopMinAngleDeg) << "budget " << budget;
  }
}

TEST(SurfaceRemesh, AngleSmoothingSearchesRepeatsAndHandsOver) {
  // The vertices of poor triangles whose move towards the neighbours' mean does not raise their
  // smallest angle get a pattern search over their patch. Mutation check (search disabled): at
  // budget 300 the smallest angle is 18.27 degrees instead of 21.74, at budget 600 two triangles
  // stay under 30 degrees instead of none.
  const LabelImage img = island_under_layer();
  const TriSurface input = extract(img, 3).surface;
  const SurfaceProjection on_input(input);
  const double diagonal = img.spacing.norm();
  EXPECT_GT(remeshed_angles(input, on_input, 300, diagonal).smallest, kPolishedMinAngleDeg);
  EXPECT_EQ(remeshed_angles(input, on_input, 600, diagonal).under_30, 0u);
  // The passes repeat until one moves nothing: a vertex moves once per pass by a bounded step,
  // and a poor triangle's neighbours often have to move first. Mutation check (three passes, the
  // old fixed count): 19.85 degrees at budget 400.
  EXPECT_GT(remeshed_angles(input, on_input, 400, diagonal).smallest, kRepeatedPolishMinAngleDeg);
  // A vertex next to a junction often stands for input vertices that its own triangles only just
  // reach (within the approximation bound); moving it away would leave them behind. The angle
  // smoothing may hand such an input vertex to a neighbour whose triangles reach it. Mutation
  // check (no hand-over): at budget 200 the smallest angle is 18.38 degrees instead of 26.11, at
  // budget 450 two triangles stay under 30 degrees instead of none.
  const AngleStats at_200 = remeshed_angles(input, on_input, 200, diagonal);
  EXPECT_GT(at_200.smallest, kHandoffMinAngleDeg);
  EXPECT_EQ(remeshed_angles(input, on_input, 450, diagonal).under_30, 0u);
  // Last, the longest edge of a poor triangle is split where that raises the smallest angle
  // around it, and the budget is met again. Mutation check (no such split): at budget 200 two
  // triangles stay under 30 degrees (smallest 26.11) instead of none (30.11).
  EXPECT_EQ(at_200.under_30, 0u);
  // The pattern search also moves curve vertices along their junction. Mutation check (surface
  // vertices only): at budget 125 two triangles stay under 30 degrees instead of one. (Its real
  // effect is on the phantom: 21K minimum angle 25.61 -> 30.06 degrees, README.)
  EXPECT_LE(remeshed_angles(input, on_input, 125, diagonal).under_30, 1u);
}

TEST(SurfaceRemesh, FlipsLeaveNoVertexWithThreeTriangles) {
  // A vertex inside a patch with three triangles bounds their smallest angle by half the smallest
  // angle of the triangle around them; a flip that would leave one is refused (the phantom's 2.1K
  // minimum angle was such a vertex: 14.8 degrees, 23.6 since). Mutation check (flips allowed down
  // to three triangles): one such vertex at budget 200, smallest angle 16.00 degrees.
  const LabelImage img = island_under_layer();
  const TriSurface input = extract(img, 3).surface;
  const SurfaceProjection on_input(input);
  const RemeshResult r = remesh(input, on_input, 200, img.spacing.norm());
  ASSERT_TRUE(r.checks.valid());
  std::vector<int> triangles_at(r.surface.points.size(), 0);
  for (const auto& t : r.surface.triangles)
    for (int v : t) ++triangles_at[static_cast<std::size_t>(v)];
  std::vector<char> on_junction(r.surface.points.size(), 0);
  for (const auto& j : r.surface.junctions)
    for (int v : j) on_junction[static_cast<std::size_t>(v)] = 1;
  int three = 0;
  for (std::size_t v = 0; v < triangles_at.size(); ++v) three += triangles_at[v] == 3 && !on_junction[v];
  EXPECT_EQ(three, 0);
}


TEST(SurfaceRemesh, RepairAroundPoorTrianglesIsKeptOnlyWhenItIsBetter) {
  // The island's small junction loops leave triangles under 30 degrees after the polish at these
  // budgets. Each result is compared with the same remeshing without the repair (the polished
  // surface): a kept repair is no worse in smallest angle and Q_min and better in one of them or
  // P30 (improves_table1_minima); a discarded one returns the polished surface bit for bit, with
  // its counters. Measured when written: kept at 80, 110 and 120; discarded at 100 and 130 (the
  // repair's smallest angle was lower: 19.02 against 19.03 and 26.48 against 29.90 degrees).
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
  FoldedLayersParams folds;
  folds.size_mm = 60.0;  // 60^3 voxels of 1 mm
  folds.layer_thickness_mm = {3.5, 3.5, 3.5, 3.5};
  folds.deep_radius_mm = 3.0;
  const LabelImage img = make_folded_layers(folds);
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
