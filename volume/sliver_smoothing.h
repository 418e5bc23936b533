// Sliver removal by moving vertices, keeping every tissue's boundary where it is (or on a reference surface).
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
// Optionally (a `SurfaceProjector` is given; the surface pipeline gives its input surface) also
// vertices on a curved boundary or interface: every face at them lies on one region pair p|q,
// with oriented normals (p into q) within 45 degrees of the first one's (no crease, no fold at
// the rim of a thin sheet), and they move over the reference surface's p|q patch (each trial
// position projected onto it), so the mesh's boundary keeps its vertices on the reference surface
// and only its triangles between them change (a tissue's volume changes by the second-order
// difference). A projection that lands further away than twice the step (the far side of a thin
// sheet of tissue) is not tried. This kind takes precedence over near-planar.
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

#include <Eigen/Core>

#include <cstddef>
#include <functional>

namespace tissuemesh {

/// Moves `x` (mm) to its closest point on the reference surface's patch between regions p < q
/// (tissue ids, 0 = outside); false when the reference has no such patch.
using SurfaceProjector = std::function<bool(int p, int q, Eigen::Vector3d& x)>;

struct SliverSmoothingResult {
  std::size_t moved_vertices = 0;  ///< vertex moves kept (a vertex moved in two passes counts twice)
  std::size_t moved_on_surface = 0;  ///< of these, moves over a curved boundary or interface
  std::size_t passes = 0;          ///< sweeps over the bad tets
};

/// Moves free and planar vertices of tets with a dihedral angle below `target_deg` (degrees), at most
/// `max_passes` sweeps. Requires mesh.points.size() < kMaxFaceKeyNodes (core/face_key.h).
/// `near_planar_deg` (degrees; 0 = exactly flat patches only) and `onto_surface` (empty = none)
/// as above.
SliverSmoothingResult smooth_slivers(TetMesh& mesh, double target_deg, double near_planar_deg = 0.0,
                                     const SurfaceProjector& onto_surface = {}, int max_passes = 4);

}  // namespace tissuemesh
