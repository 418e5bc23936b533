// ThicknessSize: an upper bound on the surface remesher's edge length from the local thickness of
// the tissues (image/local_thickness.h), so that a sheet or tube thinner than the edge length is
// remeshed with edges that fit it, instead of two sides a fraction of an edge apart that the
// remesher's guards can neither coarsen nor keep well shaped.
//
// At a point p (LPS mm) the bound is max(ratio * t, floor_mm), t the smallest local thickness of
// the 8 voxels around p (the voxels of both tissues an interface point lies between), +infinity
// where no thin voxel is near (thickness at least `cap_mm`; outside, id 0, is never thin: it is
// not meshed). Units mm. Queries are O(1) and may run on several threads at once.
#pragma once

#include "core/label_image.h"

#include <Eigen/Core>

#include <array>
#include <vector>

namespace tissuemesh {

class ThicknessSize {
 public:
  /// `ids`: tissue ids (0 = outside); thicknesses under `cap_mm` (> 0) bound the size. `ratio` (> 0):
  /// edge length per mm of thickness; `floor_mm` (> 0): the smallest bound. Throws InputError for
  /// parameters out of range.
  ThicknessSize(const LabelImage& ids, double cap_mm, double ratio, double floor_mm);

  /// The bound at p (mm), +infinity where nothing thin is near.
  double operator()(const Eigen::Vector3d& p) const;
  /// Voxels whose thickness bounds the size (under cap_mm).
  std::size_t thin_voxels() const { return thin_voxels_; }

 private:
  std::array<int, 3> dims_;
  Eigen::Vector3d origin_;
  Eigen::Matrix3d to_index_;  ///< physical offset from origin -> continuous voxel index
  std::vector<float> bound_;  ///< per voxel, mm (+infinity: none)
  std::size_t thin_voxels_ = 0;
};

}  // namespace tissuemesh
