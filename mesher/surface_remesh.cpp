#include "mesher/surface_remesh.h"

#include "core/errors.h"
#include "mesher/remesh_complex.h"

#include <algorithm>
#include <cmath>

namespace tissuemesh {
namespace {

/// Triangles with an angle under this are poor (the threshold of the paper's P30 column); the
/// last passes move their vertices to raise the smallest angle around them.
constexpr double kPoorAngleDeg = 30.0;
/// Angle-improving smoothing passes (measured on the phantom: the third moves few vertices).
constexpr int kAngleSmoothingPasses = 3;
/// Edges shorter than this times h after a round's collapses have converged are stuck (kept by a
/// corner or a guard), and the size is capped around them (mesher/graded_size_cap.h).
/// (0.5: below the collapse threshold 4/5 with margin; 0.65 gave the same phantom meshes.) From
/// the second round on: the first coarsens the fine extraction and leaves nothing converged.
constexpr double kStuckBelow = 0.5;

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
    // The first rounds coarsen a fine extraction by a large factor: collapse until stable.
    for (int k = 0; k < 20; ++k)
      if (m.collapse_short() == 0) break;
    if (it >= 1) m.grade_stuck_edges(kStuckBelow);
    m.split_long();
    m.flip_all();
    m.relax();
    if (budget && (it == rounds / 3 || it == 2 * rounds / 3))
      m.L *= std::sqrt(static_cast<double>(m.vertices()) / static_cast<double>(target));
  }
  if (budget && !m.match_count(target))
    throw MeshingError("surface remeshing could not reach the vertex budget " + std::to_string(target) + " (at " +
                       std::to_string(m.vertices()) + ")");
  for (int k = 0; k < 3; ++k) {
    m.flip_all();
    m.relax();
  }
  m.flip_all();
  std::size_t smoothed = 0;
  for (int k = 0; k < kAngleSmoothingPasses; ++k) {
    smoothed += m.smooth_poor(kPoorAngleDeg * M_PI / 180.0);
    m.flip_all();
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
