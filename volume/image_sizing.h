// Element sizes from the image and an element budget (direct pipeline, `direct.target_tets`).
//
// The edge length field (mm) is built on blocks of b x b x b voxels (b chosen so that the grid has
// at most ~2 M blocks; a block takes the smallest value of its voxels):
//   l0(v) = min(ratio * local_thickness(v), cap(v))   ratio = `thickness_edge_ratio`; cap from
//                                                      the fixed sizes (refined tissue, per tissue)
//   l(v)  = min over blocks u of beta * l0(u) + growth * |u - v|     (grading, Lipschitz `growth`)
//   edge(v) = clamp(l(v), min_edge, s)
// and the global edge s (mm) is chosen so that the predicted tet count
//   N = sum over tissue voxels of voxel_volume / (tet_volume_factor * edge^3)
// meets `target_tets`. When even s = max_edge gives more than the target, the thin parts cannot
// all be resolved at this budget: beta > 1 coarsens them by the same factor, and the tissues that
// lose resolution are named. `tet_volume_factor` is the mean tet volume over edge^3 the mesher
// produces; the direct mesher corrects it from its own count and solves again.
#pragma once

#include "core/label_image.h"

#include <Eigen/Core>

#include <array>
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

namespace tissuemesh {

struct ImageSizingParams {
  std::size_t target_tets = 0;        ///< the budget, tets (> 0)
  double thickness_edge_ratio = 1.0;  ///< edge / local thickness in thin parts
  double growth = 0.3;                ///< mm of edge per mm of distance (grading)
  double min_edge_mm = 0.0;           ///< smallest edge, mm (> 0)
  double max_edge_mm = 0.0;           ///< largest edge, mm (>= min_edge_mm)
  double tet_volume_factor = 0.015;   ///< mean tet volume / edge^3 (> 0)
};

/// A tissue whose thin parts get elements coarser than `thickness_edge_ratio` times their thickness.
struct CoarsenedTissue {
  std::string tissue;
  double thin_volume_mm3 = 0.0;  ///< volume of its voxels thinner than the budget resolves
};

struct ImageSizing {
  std::array<int, 3> blocks{0, 0, 0};  ///< grid of blocks
  int block = 1;                       ///< voxels per block edge
  Eigen::Vector3d spacing{1, 1, 1};    ///< voxel spacing, mm
  std::vector<float> graded;           ///< l per block, before the global cap, mm
  std::vector<std::uint32_t> tissue_voxels;  ///< tissue (non-zero id) voxels per block
  double global_edge_mm = 0.0;         ///< s
  double min_edge_mm = 0.0;
  double thickness_scale = 1.0;        ///< beta
  double predicted_tets = 0.0;
  std::vector<CoarsenedTissue> coarsened;

  /// Edge length (mm) at a point given in voxel-scaled coordinates (voxel (i,j,k) at
  /// (i sx, j sy, k sz)): the smallest value of the blocks of the 8 voxels around it.
  double edge_at(double x, double y, double z) const;
  /// Predicted tets for a global edge s and the current tet_volume_factor.
  double predict(double s, double tet_volume_factor) const;
  /// The global edge (mm) whose prediction meets `target` (clamped to [min_edge, max_edge]).
  double solve(double target, double tet_volume_factor, double max_edge_mm) const;
};

/// `ids`: tissue ids (0 = outside, not meshed). `thickness`: image/local_thickness.h, per voxel,
/// mm. `cap(i, j, k)`: the largest edge (mm) the fixed sizes allow at voxel (i, j, k).
/// `names[t-1]` names tissue id t. Throws InputError if the parameters are out of range.
ImageSizing size_from_image(const LabelImage& ids, const std::vector<float>& thickness,
                            const std::function<double(int, int, int)>& cap, const std::vector<std::string>& names,
                            const ImageSizingParams& params);

}  // namespace tissuemesh
