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
SliverSmoothingResult smooth_slivers(TetMesh& mesh, double target_deg, int max_passes = 4);

}  // namespace tissuemesh
