// Carrying a label image through a deformation of its mesh: the prone labels resampled into the
// supine shape, for overlay on a supine MRI (docs/prone-to-supine.md, "Images").
//
// The output grid has the input's spacing and direction and covers the deformed mesh (its
// bounding box in the input's index frame, one voxel of margin). Each output voxel centre y that
// lies in a deformed tet takes the label of the input voxel nearest to the matching point of the
// undeformed configuration (same barycentric coordinates of the tet's corners: the inverse map);
// voxels outside the deformed mesh are 0 (background). A voxel centre on a face shared by two tets
// takes the lower-numbered tet (both give the same point). Points in LPS mm.
#pragma once

#include "core/label_image.h"
#include "core/model.h"

#include <Eigen/Core>

#include <vector>

namespace tissuemesh {

/// `labels`: the image the undeformed configuration was segmented from; `model`: the mesh (its
/// elements' corners are used); `undeformed`, `deformed`: every model node's position in the two
/// configurations (mm). Throws InputError when the output grid would exceed 2^31 voxels (a
/// deformation far larger than the image) and std::invalid_argument for mismatched sizes.
LabelImage transfer_labels(const LabelImage& labels, const Model& model, const std::vector<Eigen::Vector3d>& undeformed,
                           const std::vector<Eigen::Vector3d>& deformed);

}  // namespace tissuemesh
