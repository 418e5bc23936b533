#include "mesher/surface_remesh.h"

#include "core/errors.h"
#include "mesher/remesh_complex.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
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
/// these (flips only around the moved vertices, mesher/remesh_complex.h flip_around): 21K
/// triangles with an angle under 30 degrees 18 -> 10 of 42,513; 2.1K 69 -> 31 of 4,413, minimum
/// angle 10.4 -> 14.8 degrees.
constexpr int kAngleSmoothingPasses = 40;
/// Edges shorter than this times h after a round's collapses have converged are stuck (kept by a
/// corner or a guard), and the size is capped around them (mesher/graded_size_cap.h).
/// (0.5: below the collapse threshold 4/5 with margin; 0.65 gave the same phantom meshes.) From
/// the second round on: the first coarsens the fine extraction and leaves nothing converged.
constexpr double kStuckBelow = 0.5;

std::string format_mm(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.3f", v);
  return buffer;
}

}  // namespace

RemeshResult remesh_surface(const TriSurface& input, const SurfaceProjection& projection, const RemeshOptions& options,
                            Progress& progress) {
  if (options.target_vertices <= 0 && !(options.target_edge_mm > 0.0))
    throw InputError("surface remeshing needs a vertex budget or a target edge length");
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
  auto stage = progress.stage("surface remeshing");
  const int rounds = std::max(1, options.iterations);
  for (int it = 0; it < rounds; ++it) {
    // The first rounds coarsen a fine extraction by a large factor: collapse until stable, dropping
    // the dead vertices and triangles after each sweep (at 21K, 183,803 of the 203,882 vertices go).
    for (int k = 0; k < 20; ++k) {
      const std::size_t collapsed = m.collapse_short();
      m.compact();
      if (collapsed == 0) break;
    }
    if (it >= 1) m.grade_stuck_edges(kStuckBelow);
    m.split_long();
    m.flip_all();
    m.relax();
    stage.note("round " + std::to_string(it + 1) + "/" + std::to_string(rounds) + ": " + std::to_string(m.vertices()) +
               " vertices at edge length L " + format_mm(m.L) + " mm");
    if (budget && (it == rounds / 3 || it == 2 * rounds / 3))
      m.L *= std::sqrt(static_cast<double>(m.vertices()) / static_cast<double>(target));
  }
  auto meet_budget = [&] {
    if (budget && !m.match_count(target))
      throw MeshingError("surface remeshing could not reach the vertex budget " + std::to_string(target) + " (at " +
                         std::to_string(m.vertices()) + ")");
  };
  meet_budget();
  for (int k = 0; k < 3; ++k) {
    m.flip_all();
    m.relax();
  }
  m.flip_all();
  const double poor = kPoorAngleDeg * M_PI / 180.0;
  std::size_t smoothed = 0;
  auto smooth_until_still = [&] {
    for (int k = 0; k < kAngleSmoothingPasses; ++k) {
      std::vector<int> moved;
      m.smooth_poor(poor, moved);
      if (moved.empty()) break;
      smoothed += moved.size();
      m.flip_around(moved);
    }
  };
  smooth_until_still();
  stage.note("budget met (" + std::to_string(m.vertices()) + " vertices), flips, relaxation, " +
             std::to_string(smoothed) + " angle-improving moves");
  // A poor triangle no move could fix may get better by splitting its longest edge (split_poor);
  // the budget is then met again and the smoothing repeats. Measured on the phantom: one split at
  // 21K (P30 6 -> 2 angles, Q_min 0.445 -> 0.501), none at 2.1K.
  std::vector<int> added;
  if (m.split_poor(poor, added) > 0) {
    m.flip_around(added);
    meet_budget();
    smooth_until_still();
  }
  RemeshResult r;
  r.surface = m.result(input);
  r.checks = check_surface(r.surface);
  r.edge_length_mm = m.L;
  r.splits = m.splits;
  r.collapses = m.collapses;
  r.flips = m.flips;
  r.angle_moves = smoothed;
  return r;
}

}  // namespace tissuemesh
