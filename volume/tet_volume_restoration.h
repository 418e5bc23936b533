// Volume restoration of a tet mesh: its boundary and interface nodes move by the patch offsets of
// surface/volume_restoration.h, computed on the mesh's own multi-material surface
// (quality/mesh_interfaces.h), so that every tissue's tets fill its reference volume (e.g. its
// voxel volume) again.
//
// Why after meshing: CGAL Mesh_3 resamples the surface it is given (volume/complex_mesher.h), and
// the chords of a coarser resampling cut the convex side of every curved sheet and tube, so a
// restored surface loses volume again in the tets; the direct pipeline (volume/direct_mesher.h)
// loses it to chords, label smoothing and the half voxels beyond the border voxels' centres, and
// restores it last with each node's total move bounded by one voxel. Moving the nodes of the
// mesh's own boundary restores the volume where it is.
//
// Tets must stay positively oriented and keep their quality: a round whose moves would invert a
// tet around a moved node, or take its smallest dihedral under 10 degrees (under its own, if it
// was already smaller), holds that tet's surface nodes and their neighbours, and the offsets are
// solved again (the rounds of volume_restoration.h, with this rule in place of its surface
// checks: the mesh's surface may touch itself at a vertex, which tets allow). Interior nodes do
// not move, so a sliver repair's mesh stays repaired.
// Units mm, mm^3. Deterministic.
#pragma once

#include "core/tet_mesh.h"
#include "surface/volume_restoration.h"

#include <cstddef>
#include <limits>
#include <map>

namespace tissuemesh {

struct TetVolumeRestoration {
  VolumeRestoration offsets;    ///< the rounds of patch offsets on the mesh's surface
  std::size_t nodes_moved = 0;  ///< boundary and interface nodes that moved
  double max_offset_mm = 0.0;   ///< largest move
};

/// Restores `mesh` as above towards `reference_mm3` (tissue id -> mm^3, > 0), no node moving
/// further than `max_total_move_mm` in all (infinity: no bound). The mesh must be conforming (a
/// face in at most two tets) with every tet positively oriented. Throws InputError for a reference
/// naming an unknown tissue or not > 0, a bound not > 0, or a non-conforming mesh.
TetVolumeRestoration restore_tet_volumes(TetMesh& mesh, const std::map<int, double>& reference_mm3,
                                         double max_total_move_mm = std::numeric_limits<double>::infinity());

}  // namespace tissuemesh
