// Sliver removal by moving vertices (max-min dihedral smoothing: Freitag and Ollivier-Gooch,
// "Tetrahedral mesh improvement using swapping and smoothing", 1997), keeping every tissue's
// boundary where it is (or on a reference surface). The vertices that move:
//  - free: on no boundary and no interface face; boundary, interfaces and volumes unchanged;
//  - planar: all boundary or interface faces at it on one region pair and in one plane (normals
//    within 1e-6 rad); slides within that plane, everything unchanged;
//  - near-planar (near_planar_deg > 0): faces on one region pair, normals within near_planar_deg
//    of the first one's; moves in the plane that keeps its tissue's volume (to round-off), the
//    surface moving off its place by at most sin(2 near_planar_deg) times the move;
//  - on surface (`onto_surface` given): faces on one region pair p|q, oriented normals within 45
//    degrees of the first one's; moves over the reference surface's p|q patch, so the boundary
//    keeps its vertices on that surface (volumes change to second order). Takes precedence over
//    near-planar.
// Junction and corner vertices never move, except as below. For each tet below the target, in order of quality
// then index, each of its movable vertices is moved by a pattern search to maximise the smallest
// dihedral angle over its star, every tet kept positively oriented. Serial and deterministic.
//
// Off the surface (offset_edge_ratio > 0): the last resort for flat tets whose four vertices are
// all on boundaries or interfaces (a sheet of tissue pinched thinner than its edges, a crease):
// every vertex that is not free, junctions and corners included, may also move off its surface,
// anywhere within offset_edge_ratio times its mean edge length (over its star, when the call
// began) of where it was then, in steps of a quarter of that bound and no further once its star
// is over the target. A bound relative to the edges is the same on a fine and on a coarse
// mesh: what thickens a flat tet is an offset in proportion to its edges. The boundary and
// interfaces then move by at most that distance at those vertices, and the tissues' volumes by at
// most that distance times the area of their faces there.
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
  std::size_t moved_off_surface = 0; ///< of these, moves of vertices off their surface (offset_edge_ratio)
  double max_offset_mm = 0.0;        ///< farthest such a vertex ended from where it was, mm
  std::size_t passes = 0;          ///< sweeps over the bad tets
};

/// Moves free and planar vertices of tets with a dihedral angle below `target_deg` (degrees), at most
/// `max_passes` sweeps. Requires mesh.points.size() < kMaxFaceKeyNodes (core/face_key.h).
/// `near_planar_deg` (degrees; 0 = exactly flat patches only) and `onto_surface` (empty = none)
/// as above; `offset_edge_ratio` (0 = never off the surface) as above.
SliverSmoothingResult smooth_slivers(TetMesh& mesh, double target_deg, double near_planar_deg = 0.0,
                                     const SurfaceProjector& onto_surface = {}, int max_passes = 4,
                                     double offset_edge_ratio = 0.0);

}  // namespace tissuemesh
