// Sliver removal by moving vertices without changing any tissue's boundary.
//
// Flips (sliver_flips.h) cannot repair a flat tet whose bad angle sits at an edge of the boundary
// or of an interface, and CGAL's exudation cannot move vertices. Two kinds of vertices can move
// with every tissue's boundary, interfaces and volume unchanged:
//  - free vertices, on no interface and no boundary face: their star (the tets around them) lies
//    in one tissue and closes around them, and its outer faces stay where they are;
//  - planar vertices, whose boundary or interface faces all lie on one region pair and in one
//    plane (normals within 1e-6 rad; e.g. the phantom's cut chest-wall plane, where CGAL leaves
//    rows of surface vertices 0.1-0.3 mm apart midway between two protected junction curves):
//    they slide within that plane.
// Optionally (near_planar_deg > 0) also near-planar vertices, whose faces lie on one region pair
// with normals within near_planar_deg of the first one's (nearly flat patches of a curved
// interface, e.g. a thin fat layer between skin and muscle whose tets span it): they move in the
// plane orthogonal to their tissue's volume gradient (recomputed at each move), so every tissue's
// volume stays as it was (to round-off), while the surface there moves off its place by at most
// sin(2 near_planar_deg) times the move (the gradient is the area-weighted sum of the face normals).
// For each tet below the target, in order of quality then index, each of its movable vertices is
// moved by a deterministic pattern search (steps along the axes and along the normal of the face
// opposite it in its star's worst tet, projected into its plane for a planar vertex, halved from
// a quarter of its mean edge length) to maximise the smallest dihedral angle over its star, every
// tet kept positively oriented; a move is kept only when it raises that minimum, or keeps it and
// lowers the star's squared shortfall below the target (max-min dihedral
// smoothing: Freitag and Ollivier-Gooch, "Tetrahedral mesh improvement using swapping and
// smoothing", 1997). Serial and deterministic.
#pragma once

#include "core/tet_mesh.h"

#include <cstddef>

namespace tissuemesh {

struct SliverSmoothingResult {
  std::size_t moved_vertices = 0;  ///< vertex moves kept (a vertex moved in two passes counts twice)
  std::size_t passes = 0;          ///< sweeps over the bad tets
};

/// Moves free and planar vertices of tets with a dihedral angle below `target_deg` (degrees), at most
/// `max_passes` sweeps. Requires mesh.points.size() < kMaxFaceKeyNodes (mesher/face_key.h).
/// `near_planar_deg` (degrees; 0 = exactly flat patches only) as above.
SliverSmoothingResult smooth_slivers(TetMesh& mesh, double target_deg, double near_planar_deg = 0.0,
                                     int max_passes = 4);

}  // namespace tissuemesh
