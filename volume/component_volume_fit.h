// Volume fit of small enclosed components (direct pipeline, `direct.fit_island_volumes`).
//
// A small closed component (an FGT island in fat, say) is meshed as a polyhedron whose vertices
// lie on its boundary: inscribed in a convex blob, it is smaller than the blob, by tens of percent
// for one a few elements across. This step scales each such component about its volume centroid
// by lambda = (voxel volume / meshed volume)^(1/3), so that its meshed volume equals its voxel
// volume; the one tissue around it gives up the same volume. Only components whose vertices are
// shared with tets of one other tissue and none on the outer boundary qualify, lambda stays in
// [1 / max_scale, max_scale], and a move that would leave any affected tet inverted or with a
// smallest dihedral angle below min(min_dihedral_deg, its angle before) is halved (three times at
// most) or left out.
#pragma once

#include "core/tet_mesh.h"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace tissuemesh {

struct ComponentTarget {
  int tissue = 0;             ///< tissue id of the component
  double volume_mm3 = 0.0;    ///< its volume in the image, mm^3
};

struct ComponentVolumeFit {
  std::size_t fitted = 0;         ///< components scaled to their voxel volume (or part way)
  std::size_t not_enclosed = 0;   ///< components sharing vertices with a third tissue or the boundary
  std::size_t blocked = 0;        ///< components whose move would spoil a tet, left as they were
  double volume_moved_mm3 = 0.0;  ///< sum of |volume change| over the fitted components
};

/// `tet_component[t]`: index into `targets` of the component tet t belongs to, or -1. Components
/// larger than `max_voxel_volume_mm3` and those within 1 % of their target are left alone.
/// Moves only vertices; tets, tissues and connectivity stay. Deterministic.
ComponentVolumeFit fit_component_volumes(TetMesh& mesh, const std::vector<std::int32_t>& tet_component,
                                         const std::vector<ComponentTarget>& targets, double max_voxel_volume_mm3,
                                         double max_scale, double min_dihedral_deg);

}  // namespace tissuemesh
