// Voxel weights that make CGAL's labelled-image surfaces smooth (Stalling, Zöckler, Hege 1998,
// "Weighted labels for 3D image segmentation"; the method behind CGAL's generate_label_weights).
//
// weight(v) = 255 * max over labels l of (G_sigma * 1_l)(v), with 1_l the indicator of label l and
// G_sigma a Gaussian of standard deviation sigma (mm, per axis converted with the voxel spacing,
// truncated at 3 sigma). CGAL then interpolates each label's weighted indicator trilinearly, so
// boundaries become smooth while every voxel centre keeps its own label: thin layers such as a
// one-voxel skin are not lost.
#pragma once

#include "core/label_image.h"

#include <cstdint>
#include <vector>

namespace tissuemesh {

/// One weight per voxel of `ids` (same order), in 0..255. `sigma_mm` > 0.
std::vector<std::uint8_t> label_weights(const LabelImage& ids, double sigma_mm);

}  // namespace tissuemesh
