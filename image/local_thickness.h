// Local thickness of every tissue in a label image: the diameter of the largest ball that contains
// the voxel and lies inside the voxel's own label (Hildebrand & Rüegsegger 1997, "A new method for
// the model-independent assessment of thickness in three-dimensional images", J Microscopy 185).
// Used to size elements so that thin layers and small parts keep their volume.
//
// Discrete version: the boundary voxels of a label (a 6-neighbour of another label, or on the image
// border, where the meshed domain ends) are at distance 0; every voxel gets its Euclidean distance
// e to the nearest boundary voxel (Felzenszwalb & Huttenlocher 2012, "Distance transforms of
// sampled functions", separable, anisotropic spacing); each ridge voxel (e not below any of its 26
// same-label neighbours) with 2e + h < `cap_mm` paints 2e + h (h: the smallest spacing) over the
// same-label voxels within e + h/2 of it; a voxel keeps the largest value painted on it. A layer
// of an odd number n of voxels gets n*h, an even one (n-1)*h, a ball up to two voxels less than its
// diameter (never more: sizes err on the fine side); voxels no thin ridge reaches are
// "at least cap_mm" and get +infinity.
#pragma once

#include "core/label_image.h"

#include <vector>

namespace tissuemesh {

/// One value per voxel of `ids` (same order), in mm; +infinity where the thickness is at least
/// `cap_mm`. Voxels of label 0 are treated like any other label. `cap_mm` > 0. Cost: one distance
/// transform plus the painted balls (about the thin voxels times their thickness in voxels).
std::vector<float> local_thickness(const LabelImage& ids, double cap_mm);

}  // namespace tissuemesh
