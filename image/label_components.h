// Connected components of every tissue in a tissue-id image (6-connectivity): a boundary seed
// voxel, bounding box and centroid per component, for seeding every component of a volume mesher
// and for naming the parts missing from a mesh. Deterministic.
#pragma once

#include "core/label_image.h"

#include <Eigen/Core>

#include <array>
#include <cstdint>
#include <vector>

namespace tissuemesh {

struct LabelComponent {
  int tissue_id = 0;                 ///< tissue id of every voxel in it (> 0)
  std::size_t voxels = 0;            ///< number of voxels
  std::array<int, 3> seed{0, 0, 0};  ///< a voxel of the component on its boundary (first in scan order)
  std::array<int, 3> box_min{0, 0, 0}, box_max{0, 0, 0};  ///< inclusive voxel bounding box
  Eigen::Vector3d centroid_mm{0, 0, 0};                   ///< physical LPS centroid of voxel centres
};

struct ComponentMap {
  /// Sorted by tissue id, then by first voxel in scan order (deterministic).
  std::vector<LabelComponent> components;
  /// Per voxel: index into `components`, or -1 for tissue id 0 (outside).
  std::vector<std::int32_t> component_of_voxel;
};

/// Labels the 6-connected components of every non-zero id of `tissue_ids`.
ComponentMap find_components(const LabelImage& tissue_ids);

}  // namespace tissuemesh
