#include "surface/surface_remesh.h"

#include "core/errors.h"
#include "core/number_format.h"
#include "surface/remesh_complex.h"
#include "surface/surface_quality.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>

namespace tissuemesh {
namespace {

/// Triangles with an angle under this are poor (the threshold of the paper's P30 column); the
/// last passes move their vertices to raise the smallest angle around them.
constexpr double kPoorAngleDeg = 30.0;
/// Angle-improving smoothing passes at most; they stop when one moves nothing. Each pass moves a
/// vertex once, by a bounded step, so poor triangles improve over many passes. Measured on the
/// phantom (vertices moved per pass): 21K 72, 16, 17, 12, ... 1, 0 after 21 passes; 2.1K 107, 61,
/// 48, ... still 3 in the 40th. From 3 passes (each followed by a flip sweep over every edge) to
/// these (flips only around the moved vertices, surface/remesh_complex.h flip_around): 21K
/// triangles with an angle under 30 degrees 18 -> 10 of 42,513; 2.1K 69 -> 31 of 4,413, minimum
/// angle 10.4 -> 14.8 degrees.
constexpr int kAngleSmoothingPasses = 40;
/// Edges shorter than this times h after a round's collapses have converged are stuck (kept by a
/// corner or a guard), and the size is capped around them (surface/graded_size_cap.h).
/// (0.5: below the collapse threshold 4/5 with margin; 0.65 gave the same phantom meshes.) From
/// the second round on: the first coarsens the fine extraction and leaves nothing converged.
constexpr double kStuckBelow = 0.5;
/// Rounds of the repair around poor triangles (remesh_surface). Measured on the phantom (budgets
/// 1,900 / 2,300 / 19,000 / 20,000: smallest angle without repair 13.9 / 18.5 / 18.0 / 27.9
/// degrees): 2 rounds 27.6 / 26.6 / 30.0 / 30.0; 3 rounds 27.4 / 26.6 / 29.6 / 30.0; 5 rounds
/// 27.6 / 26.6 / 30.0 / 29.8 (Q_min at 19,000: 0.498, 0.483, 0.480). (Measured on an earlier
/// sequence of operations; on the present one the repair is kept at both shipped budgets,
/// bench/RESULTS.md 2026-11-27 ~15:25-16:50 UTC.)
constexpr int kRepairRounds = 2;
/// The repair's sweeps act within this many L of a poor triangle (RemeshComplex::
/// focus_on_poor_triangles): the size cap it enters around the triangle's shortest edge (length
/// l) is under L within (L - 1.5 l) / 0.4 < 2.5 L of that edge; one L more, so that the repaired
/// region ends where the size field is unchanged. Everything farther stays as polished.
constexpr double kRepairReach = 3.5;

}  // namespace

RemeshResult remesh_surface(const TriSurface& input, const SurfaceProjection& projection, const RemeshOptions& options,
                            Progress& progress) {
  if (options.target_vertices <= 0 && !(options.target_edge_mm > 0.0))
    throw InputError("surface remeshing needs a vertex budget or a target edge length");
  auto stage = progress.stage("surface remeshing");  // from the complex's construction on
  RemeshComplex m(input, projection, options);
  const bool budget = options.target_vertices > 0;
  const std::size_t target = budget ? static_cast<std::size_t>(options.target_vertices) : 0;
  if (budget) {
    if (m.corners() >= target)
      throw MeshingError("vertex budget " + std::to_string(target) + " is not above the " +
                         std::to_string(m.corners()) + " junction corners the surface must keep");
    m.L = std::sqrt(2.0 * m.weighted_area() / (std::sqrt(3.0) * static_cast<double>(target)));
  } else {
    m.L = options.target_edge_mm;
  }
  // One round: collapse until stable (the first rounds coarsen a fine extraction by a large
  // factor; at 21K, 183,803 of the 203,882 vertices go), dropping the dead vertices and triangles
  // after each sweep; then split, flip, relax.
  auto round = [](RemeshComplex& c, bool grade) {
    c.collapse_until_stable(20);
    if (grade) c.grade_stuck_edges(kStuckBelow);
    c.split_long();
    c.flip_all();
    c.relax();
  };
  const int rounds = std::max(1, options.iterations);
  for (int it = 0; it < rounds; ++it) {
    round(m, it >= 1);
    stage.note("round " + std::to_string(it + 1) + "/" + std::to_string(rounds) + ": " + std::to_string(m.vertices()) +
               " vertices at edge length L " + format_double("%.3f", m.L) + " mm");
    if (budget && (it == rounds / 3 || it == 2 * rounds / 3))
      m.L *= std::sqrt(static_cast<double>(m.vertices()) / static_cast<double>(target));
  }
  const double poor = kPoorAngleDeg * M_PI / 180.0;
  // Budget, then polish: flips and relaxation, angle-improving smoothing until nothing moves, and
  // a split of the longest edge of a poor triangle no move could fix (split_poor; the budget is
  // then met again and the smoothing repeats; measured on the phantom: one split at 21K, P30 6 ->
  // 2 angles, Q_min 0.445 -> 0.501, none at 2.1K). Returns the angle-improving moves.
  auto finish = [&](RemeshComplex& c) {
    auto meet_budget = [&] {
      if (budget && !c.match_count(target))
        throw MeshingError("surface remeshing could not reach the vertex budget " + std::to_string(target) + " (at " +
                           std::to_string(c.vertices()) + ")");
    };
    meet_budget();
    for (int k = 0; k < 3; ++k) {
      c.flip_all();
      c.relax();
    }
    c.flip_all();
    std::size_t smoothed = 0;
    auto smooth_until_still = [&] {
      for (int k = 0; k < kAngleSmoothingPasses; ++k) {
        std::vector<int> moved;
        c.smooth_poor(poor, moved);
        if (moved.empty()) break;
        smoothed += moved.size();
        c.flip_around(moved);
      }
    };
    smooth_until_still();
    // Vertices of three or four triangles left in poor triangles go (collapse_poor); the budget
    // is met again by splitting the relatively longest edges, and the smoothing repeats.
    if (c.collapse_poor(poor) > 0) {
      meet_budget();
      c.flip_all();
      smooth_until_still();
    }
    std::vector<int> added;
    if (c.split_poor(poor, added) > 0) {
      c.flip_around(added);
      meet_budget();
      smooth_until_still();
    }
    return smoothed;
  };
  std::size_t smoothed = finish(m);
  TriSurface result = m.result(input);
  const SurfaceQuality first = surface_quality(result);
  stage.note("budget met (" + std::to_string(m.vertices()) + " vertices), polished: smallest angle " +
             format_double("%.2f", first.min_angle_deg) + " deg, Q_min " + format_double("%.4f", first.q_min) + ", " +
             std::to_string(smoothed) + " angle-improving moves");
  // Repair of what the polish left under 30 degrees: cap the size around each poor triangle's
  // shortest edge, remesh there again (kRepairRounds rounds) and polish again, on a copy kept only
  // when it improves the Table 1 minima (improves_table1_minima); otherwise, or when the repair
  // fails, the polished complex stays, unchanged.
  RemeshComplex* chosen = &m;
  SurfaceQuality quality = first;  // of `result`, the chosen complex's surface
  std::unique_ptr<RemeshComplex> repaired;
  if (options.repair && first.p30_percent > 0.0) {
    auto trial = std::make_unique<RemeshComplex>(m);
    trial->focus_on_poor_triangles(poor, kRepairReach * m.L);
    const std::size_t capped = trial->cap_poor_triangles(poor);
    try {
      for (int k = 0; k < kRepairRounds; ++k) round(*trial, false);
      const std::size_t trial_moves = finish(*trial);
      trial->unfocus();
      TriSurface trial_result = trial->result(input);
      const SurfaceQuality q = surface_quality(trial_result);
      const bool keep = improves_table1_minima(first, q);
      stage.note("repair around " + std::to_string(capped) + " triangles under 30 deg: smallest angle " +
                 format_double("%.2f", q.min_angle_deg) + " deg, Q_min " + format_double("%.4f", q.q_min) +
                 (keep ? " (kept)" : " (not better than " + format_double("%.2f", first.min_angle_deg) + " deg, Q_min " +
                                         format_double("%.4f", first.q_min) + ": discarded)"));
      if (keep) {
        repaired = std::move(trial);
        chosen = repaired.get();
        result = std::move(trial_result);
        quality = q;
        smoothed += trial_moves;  // like splits, collapses and flips: every pass that shaped the result
      }
    } catch (const MeshingError& e) {
      // The repair's own budget pass or junction bookkeeping failed: the polished result stands.
      stage.note("repair around " + std::to_string(capped) + " triangles under 30 deg failed (" + e.what() +
                 "): discarded");
    }
  }
  // Last, quality-raising moves around triangles under kQualitySmoothingBelow, on the chosen
  // complex: they never lower its Q_min nor raise its count of angles under 30 degrees, and never
  // take its smallest angle below min(its value, 30 degrees) (RemeshComplex::smooth_low_quality).
  // At most as many passes as the angle smoothing; on the phantom they stop after 1-5 moves.
  std::size_t quality_moves = 0;
  if (quality.q_min < kQualitySmoothingBelow) {
    for (int k = 0; k < kAngleSmoothingPasses; ++k) {
      std::vector<int> moved;
      chosen->smooth_low_quality(kQualitySmoothingBelow, poor, moved);
      if (moved.empty()) break;
      quality_moves += moved.size();
    }
    if (quality_moves > 0) result = chosen->result(input);
    stage.note("quality smoothing around triangles under Q " + format_double("%.3f", kQualitySmoothingBelow) + ": Q_min " +
               format_double("%.4f", quality.q_min) + " -> " + format_double("%.4f", surface_quality(result).q_min) + ", " +
               std::to_string(quality_moves) + " moves");
  }
  RemeshResult r;
  r.surface = std::move(result);
  r.checks = check_surface(r.surface);
  r.edge_length_mm = chosen->L;
  r.splits = chosen->splits;
  r.collapses = chosen->collapses;
  r.flips = chosen->flips;
  r.angle_moves = smoothed;
  r.quality_moves = quality_moves;
  r.partitioned_sweeps = chosen->partitioned_sweeps;
  return r;
}

}  // namespace tissuemesh
