// The radius-edge ratio a triangle surface forces on every tet mesh that keeps its triangles as
// faces: TetGen with -Y (mesher/tetgen_mesher.h), and the mesh the surface was taken from
// (mesher/mesh_interfaces.h). Issue #6 asks TetGen's mesh for a ratio <= 2; this says how far
// below that the input lets any such mesh go.
//
// Bound: let T be a triangle with smallest angle theta and shortest edge l (the edge opposite
// theta). By the law of sines its circumradius is r = l / (2 sin theta). A tet with T as a face
// has a circumsphere through T's three corners, so its circumradius R >= r, and its shortest edge
// is at most l; hence R / shortest edge >= 1 / (2 sin theta). With -Y every input triangle is a
// face of a kept tet (the tissue on one side of it at least), so the largest ratio of the mesh is
// at least the largest 1 / (2 sin theta) over the triangles. A mesher that may split boundary
// triangles (TetGen without -Y) is not bound by it.
//
// Deterministic; O(triangles).
#pragma once

#include "core/tri_surface.h"

#include <cstddef>
#include <limits>

namespace tissuemesh {

struct ForcedRadiusEdge {
  /// Largest 1 / (2 sin theta_min) over the triangles: 0 for a surface without triangles,
  /// +infinity when a triangle has zero area.
  double ratio = 0.0;
  /// The triangle that sets it (the first of equals): index into TriSurface::triangles (its
  /// patch pair is labels[triangle]); -1 without triangles.
  int triangle = -1;
  /// That triangle's smallest interior angle, degrees; NaN without triangles.
  double min_angle_deg = std::numeric_limits<double>::quiet_NaN();
  /// Triangles whose own 1 / (2 sin theta_min) exceeds the `bound` given.
  std::size_t triangles_above_bound = 0;
};

/// The bound of the header comment for `surface`, and how many of its triangles force a ratio
/// above `bound` (e.g. tetgen.radius_edge_ratio). Throws InputError when the surface is invalid
/// (TriSurface::validate).
ForcedRadiusEdge forced_radius_edge_ratio(const TriSurface& surface, double bound);

}  // namespace tissuemesh
