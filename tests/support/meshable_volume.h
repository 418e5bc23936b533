// The volume (mm^3) the direct pipeline should mesh for one label: its voxels, less the parts
// beyond the centres of the border voxels, where CGAL's labelled image ends (half a voxel per
// border face, a quarter on an edge, an eighth at a corner).
#pragma once

#include "core/label_image.h"

namespace tissuemesh::test {

inline double meshable_volume_mm3(const LabelImage& img, std::int32_t label) {
  double v = 0.0;
  auto part = [](int i, int n) { return i == 0 || i == n - 1 ? 0.5 : 1.0; };
  for (int k = 0; k < img.dims[2]; ++k)
    for (int j = 0; j < img.dims[1]; ++j)
      for (int i = 0; i < img.dims[0]; ++i)
        if (img.at(i, j, k) == label)
          v += part(i, img.dims[0]) * part(j, img.dims[1]) * part(k, img.dims[2]);
  return v * img.voxel_volume();
}

}  // namespace tissuemesh::test
