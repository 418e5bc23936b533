// Repair of non-manifold voxel configurations before surface extraction (issue #5).
//
// The boundary of a union of voxels is a 2-manifold exactly when the set is "well-composed"
// (Latecki 1997): at every lattice point (voxel corner), both the set and its complement are
// face-connected inside the 2x2x2 block of voxels around it. Two voxels of a tissue touching only
// along an edge or at a corner (or two voxels of the complement pinched by the tissue) break it and
// would give edges shared by four triangles of one tissue or vertices joining two sheets. This pass
// makes every region (tissue ids and 0 = outside, with the image padded by outside) well-composed by
// relabelling voxels, scanning blocks in a fixed order (deterministic). Every change raises a
// voxel's region id (outside = 0 never grows), so the repair terminates (at most as many changes
// per voxel as there are regions) where unrestricted fixes can undo each other:
//   - a region split inside a block is bridged by a lower-labelled voxel touching it, or else its
//     smallest piece joins its highest neighbouring region;
//   - a region pinching its complement gives one voxel to a higher neighbouring region, or else
//     the smallest (lower-labelled) piece of the complement is filled with the region.
// Passes repeat until none changes a voxel. Throws MeshingError when a defect remains that no
// such change can fix (only padding voxels involved) or `max_passes` is reached.
#pragma once

#include "core/label_image.h"

#include <cstddef>

namespace tissuemesh {

struct LabelRepairResult {
  std::size_t relabelled_voxels = 0;  ///< voxels whose region changed (counted once per change)
  int passes = 0;                     ///< passes run, including the final one without changes
};

/// Repairs `ids` (tissue ids, 0 = outside) in place. The image border is treated as outside.
LabelRepairResult make_well_composed(LabelImage& ids, int max_passes = 50);

/// True when every region of `ids` is well-composed (the check the repair establishes).
bool is_well_composed(const LabelImage& ids);

}  // namespace tissuemesh
