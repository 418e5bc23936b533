// LabelImage: a 3D integer label volume placed in physical space.
//
// Convention (one for the whole toolkit): physical coordinates are millimetres in the patient LPS
// frame (+x = patient Left, +y = Posterior, +z = Superior), the DICOM/ITK convention. Readers of
// RAS-based formats (NIfTI) convert on read and writers convert back.
//
// Voxel (i,j,k) has its centre at   p = origin + direction * diag(spacing) * (i,j,k)^T.
// `direction` columns are the unit LPS directions of the i, j, k axes (orthonormal, det = +-1).
// Storage is x-fastest: labels[i + nx*(j + ny*k)].
#pragma once

#include <Eigen/Core>

#include <array>
#include <cstddef>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace tissuemesh {

struct LabelImage {
  std::array<int, 3> dims{0, 0, 0};                     ///< voxels along i, j, k
  Eigen::Vector3d spacing{1.0, 1.0, 1.0};               ///< mm between voxel centres along i, j, k
  Eigen::Vector3d origin{0.0, 0.0, 0.0};                ///< LPS mm of the centre of voxel (0,0,0)
  Eigen::Matrix3d direction = Eigen::Matrix3d::Identity();  ///< columns: LPS unit axes of i, j, k
  std::vector<std::int32_t> labels;                     ///< size nx*ny*nz, x fastest

  std::size_t voxel_count() const {
    return static_cast<std::size_t>(dims[0]) * dims[1] * dims[2];
  }
  std::size_t index(int i, int j, int k) const {
    return static_cast<std::size_t>(i) + static_cast<std::size_t>(dims[0]) *
                                             (static_cast<std::size_t>(j) +
                                              static_cast<std::size_t>(dims[1]) * k);
  }
  std::int32_t at(int i, int j, int k) const { return labels[index(i, j, k)]; }

  /// Volume of one voxel in mm^3.
  double voxel_volume() const { return spacing.prod(); }

  /// 3x3 matrix M with p = origin + M * ijk (direction * diag(spacing)).
  Eigen::Matrix3d index_to_physical() const { return direction * spacing.asDiagonal(); }

  /// Physical LPS position (mm) of a continuous index (i,j,k).
  Eigen::Vector3d to_physical(const Eigen::Vector3d& ijk) const {
    return origin + index_to_physical() * ijk;
  }

  /// Number of voxels per label value, ascending by label.
  std::map<std::int32_t, std::size_t> label_counts() const;

  /// Throws InputError (naming `what`) unless dims are positive, labels.size() matches, spacing is
  /// positive and finite and direction is orthonormal to 1e-4.
  void validate(const std::string& what) const;
};

/// Three-letter orientation code of the direction matrix in LPS terms (e.g. "LPS", "RAS", "LPI"):
/// for each of i, j, k the patient direction it points most towards.
std::string orientation_code(const Eigen::Matrix3d& direction);

}  // namespace tissuemesh
