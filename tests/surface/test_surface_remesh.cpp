// Controlled-resolution remeshing of the multi-material surface (docs/surface-pipeline.md,
// "Remeshing to a vertex budget"): budget, closedness, shared interfaces, junction preservation,
// distance to the input, determinism.
#include "core/errors.h"
#include "surface/surface_checks.h"
#include "surface/surface_distance.h"
#include "surface/surface_projection.h"
#include "surface/surface_remesh.h"
#include "surface/triangle_geometry.h"
#include "support/coarse_phantom.h"
#include "support/surface_images.h"
#include "support/tolerances.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <set>
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
