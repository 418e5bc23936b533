// Controlled-resolution remeshing of a multi-material TriSurface (issue #5, step 2).
//
// All patches (region pairs p|q) are remeshed at once by local operations on the whole complex
// (Botsch & Kobbelt 2004, extended to junction curves), against a sizing field h(x) = L s(x):
//   split     edges longer than 4/3 h at their midpoint, which is projected onto the edge's patch or,
//             for a junction edge, onto its junction polyline (every triangle around it is split);
//   collapse  edges shorter than 4/5 h when no edge of the result is longer than 4/3 h: a surface
//             vertex into any neighbour across a non-junction edge, a curve vertex only into its
//             neighbour along the same junction; corners (polyline ends, where curves meet) stay;
//             the link condition (the endpoints share exactly the opposite vertices of the edge's
//             triangles) keeps every tissue's boundary a closed manifold;
//   flip      non-junction edges to the Delaunay diagonal of their two triangles (same patch),
//             when the two new triangles do not fold against each other;
//   relax     density-weighted centroidal relaxation: a surface vertex moves to the centroid of its
//             one-ring weighted by area / h^2 (a discrete centroidal Voronoi step, Lloyd on the
//             surface), tangentially, then onto its patch of the reference surface; a curve
//             vertex to the weighted midpoint of its two curve neighbours, then onto its junction.
// Every operation keeps the patch labels, the orientation and the junction polylines (their
// vertices and edges are replaced along the same curve), and refuses a move that flips a
// triangle. Shape: each vertex carries the input vertices collapsed into it, and a collapse or
// relaxation move is refused when one of them would end up farther than the approximation bound
// (max(max_deviation_mm, L/4)) from the triangles around it, or when a changed triangle would leave
// its patch by more than that bound or face away from it (a triangle bridging the two sides of a
// thin sheet); split midpoints and relaxed points that would project onto the far side of a thin
// sheet are refused too. Validity: the result is checked (mesher/surface_checks.h); where a
// tissue's boundary self-intersects, the size is halved in a ball around the intersecting
// triangles and the rounds and the budget pass repeat (at most 6 times; the last checks are
// returned, the caller decides). The vertex budget: L starts from the area (an equilateral mesh of area A at edge h has
// about 2A / (sqrt(3) h^2) vertices), is rescaled by the measured count after the first rounds, and
// a final pass collapses the shortest or splits the longest edges (relative to h) until the count
// is exactly the budget. Deterministic: every sweep visits triangles and vertices in index order. Not parallel.
#pragma once

#include "core/progress.h"
#include "core/tri_surface.h"
#include "mesher/surface_checks.h"
#include "mesher/surface_projection.h"

#include <Eigen/Core>

#include <cstddef>
#include <functional>

namespace tissuemesh {

struct RemeshOptions {
  int target_vertices = 0;      ///< total vertex budget (> 0), or 0 to use target_edge_mm
  double target_edge_mm = 0.0;  ///< edge length where s = 1 (used when target_vertices == 0)
  int iterations = 10;          ///< split/collapse/flip/relax rounds before the budget pass
  /// A collapse is refused when the removed vertex would lie farther than this from the new
  /// triangles (mm; 0 = no bound): small features keep their vertices whatever the size field says.
  double max_deviation_mm = 0.0;
  /// Relative size s(x) in (0, 1] (the density is 1 / s^2); empty = uniform.
  std::function<double(const Eigen::Vector3d&)> relative_size;
};

struct RemeshResult {
  TriSurface surface;
  SurfaceCheckReport checks;    ///< mesher/surface_checks.h of `surface`
  int refinement_rounds = 0;    ///< local refinements around self-intersections that were needed
  double edge_length_mm = 0.0;  ///< L, the size where s = 1, after the budget rescaling
  std::size_t splits = 0, collapses = 0, flips = 0;
};

/// `input` must be valid and closed per tissue (mesher/surface_checks.h), `projection` built on it.
/// Throws MeshingError when the budget is below what the junction corners need.
RemeshResult remesh_surface(const TriSurface& input, const SurfaceProjection& projection, const RemeshOptions& options,
                            Progress& progress);

}  // namespace tissuemesh
