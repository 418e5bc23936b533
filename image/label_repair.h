// Repair of non-manifold voxel configurations before surface extraction.
//
// The boundary of a union of voxels is a 2-manifold exactly when the set is well-composed
// (Latecki, "3D well-composed pictures", Graphical Models and Image Processing 59, 1997): at every
// lattice point (voxel corner), both the set and its complement are face-connected inside the
// 2x2x2 block of voxels around it. make_well_composed relabels voxels until every region (tissue
// ids and 0 = outside, the image padded by outside) is well-composed. Every change raises a
// voxel's region id, so outside (0) never grows. Deterministic (blocks scanned in a fixed order).
// Throws MeshingError when a defect remains that no such change can fix (only padding voxels
// involved) or `max_passes` is reached.
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
