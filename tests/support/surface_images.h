// Small generated label images and their extraction, shared by the surface-pipeline tests
// (docs/surface-pipeline.md): nested spheres on anisotropic voxels, a thin shell, and three
// touching boxes with a triple junction.
#pragma once

#include "core/label_image.h"
#include "core/progress.h"
#include "image/folded_layers.h"
#include "surface/surface_extraction.h"

#include <array>
#include <functional>
#include <string>
#include <vector>

namespace tissuemesh::test {

inline LabelImage make_image(std::array<int, 3> dims, Eigen::Vector3d spacing,
                      const std::function<int(int, int, int)>& label_at) {
  LabelImage img;
  img.dims = dims;
  img.spacing = spacing;
  img.origin = {-3.0, 2.0, 7.0};
  img.labels.resize(img.voxel_count());
  for (int k = 0; k < dims[2]; ++k)
    for (int j = 0; j < dims[1]; ++j)
      for (int i = 0; i < dims[0]; ++i) img.labels[img.index(i, j, k)] = label_at(i, j, k);
  return img;
}

/// Layers folding with a period of 3 voxels (image/folded_layers.h) in a 60^3 image of 1 mm, layers
/// 3.5 mm thick around a deep ball of 3 mm: at a 4,000-vertex budget the edges (about 3.5 mm) are
/// longer than the folds' period. Tissue ids 1..7.
inline LabelImage folds_every_three_voxels() {
  FoldedLayersParams folds;
  folds.size_mm = 60.0;
  folds.layer_thickness_mm = {3.5, 3.5, 3.5, 3.5};
  folds.deep_radius_mm = 3.0;
  return make_folded_layers(folds);
}

/// Outer ball (id 1, radius 9 mm) with an inner ball (id 2, radius 5 mm) on anisotropic voxels.
inline LabelImage nested_spheres() {
  const Eigen::Vector3d spacing(1.0, 1.0, 1.5);
  return make_image({26, 26, 18}, spacing, [&](int i, int j, int k) {
    const Eigen::Vector3d p((i - 12.5) * spacing[0], (j - 12.5) * spacing[1], (k - 8.5) * spacing[2]);
    return p.norm() < 5.0 ? 2 : p.norm() < 9.0 ? 1 : 0;
  });
}

/// A ball (id 1, radius 6 mm) in a shell one voxel thick (id 2, out to 7 mm): the two sides of the
/// shell are closer than the edge length of any coarse budget.
inline LabelImage thin_shell() {
  return make_image({20, 20, 20}, {1.0, 1.0, 1.0}, [](int i, int j, int k) {
    const double r = Eigen::Vector3d(i - 9.5, j - 9.5, k - 9.5).norm();
    return r < 6.0 ? 1 : r < 7.0 ? 2 : 0;
  });
}

/// Boxes 1 and 2 side by side (x < 15 | x >= 15), box 3 on top of both (y >= 15): a triple
/// junction 1|2|3 along the straight line x = 14.5, y = 14.5 (voxel-index units, spacing 1).
inline LabelImage three_boxes() {
  return make_image({30, 30, 20}, {1.0, 1.0, 1.0}, [](int i, int j, int k) {
    if (i < 5 || i >= 25 || j < 5 || j >= 25 || k < 5 || k >= 15) return 0;
    return j >= 15 ? 3 : i < 15 ? 1 : 2;
  });
}

/// A slab (id 1) under a layer two voxels thick (id 2, like skin), with an island (id 3) of 2 x 2 x 2
/// voxels in the slab touching the layer: the small 1|2|3 junction loops around the contact are far
/// shorter than the edges of a coarse budget (like a small fgt island touching the skin).
inline LabelImage island_under_layer() {
  return make_image({30, 30, 20}, {1.0, 1.0, 1.0}, [](int i, int j, int k) {
    if (i < 5 || i >= 25 || j < 5 || j >= 25 || k < 5 || k >= 15) return 0;
    if (k >= 13) return 2;
    return i >= 14 && i < 16 && j >= 14 && j < 16 && k >= 11 ? 3 : 1;
  });
}

/// The test images are built voxel by voxel, some with one-voxel features on purpose: islands are
/// kept unless `min_island_voxels` says otherwise (image/small_islands.h).
inline SurfaceExtraction extract(const LabelImage& img, int n_tissues, int iterations = 10, int min_island_voxels = 1) {
  std::vector<std::string> names;
  for (int i = 1; i <= n_tissues; ++i) names.push_back("t" + std::to_string(i));
  Progress progress;
  SurfaceParams params;
  params.relaxation_iterations = iterations;
  params.min_island_voxels = min_island_voxels;
  return extract_surface(img, names, params, progress);
}

}  // namespace tissuemesh::test
