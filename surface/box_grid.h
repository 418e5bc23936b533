// BoxGrid: a fixed uniform grid of axis-aligned boxes, built once, for finding the boxes near a
// point or a cell (the extraction's pair search, surface/intersecting_pairs.h, and the patch
// projection, surface/patch_grid.h). TriangleGrid (surface/triangle_grid.h) is the incremental one
// the remesher updates as it goes.
//
// Each entered item is listed in every cell its box touches, each cell's list in ascending item
// order (a counting sort: two passes over the boxes, one array). The cells are `cell_per_extent`
// times the entered boxes' mean extent (largest side), over the entered boxes' bounding box, and
// grow by 1.25x until there are at most kMaxCells of them. A point outside maps to the nearest
// border cell. Queries are const and may run from several threads.
#pragma once

#include <Eigen/Core>

#include <cstdint>
#include <vector>

namespace tissuemesh {

class BoxGrid {
 public:
  /// Items i with entered[i] set (every item when `entered` is empty), boxes [lo[i], hi[i]] (mm).
  BoxGrid(const std::vector<Eigen::Vector3d>& lo, const std::vector<Eigen::Vector3d>& hi, const std::vector<char>& entered,
          double cell_per_extent);

  /// The cell holding p, clamped to the grid (no int overflow for a point far away or NaN).
  Eigen::Array3i cell_of(const Eigen::Vector3d& p) const;
  std::int64_t index(const Eigen::Array3i& c) const { return (static_cast<std::int64_t>(c[2]) * dims_[1] + c[1]) * dims_[0] + c[0]; }
  std::int64_t cells() const { return static_cast<std::int64_t>(start_.size()) - 1; }
  /// Cell `c`'s items: [begin(c), end(c)), ascending.
  const int* begin(std::int64_t c) const { return list_.data() + start_[static_cast<std::size_t>(c)]; }
  const int* end(std::int64_t c) const { return list_.data() + start_[static_cast<std::size_t>(c) + 1]; }
  const Eigen::Vector3d& origin() const { return origin_; }  ///< lower corner of cell (0, 0, 0)
  double cell() const { return cell_; }                      ///< cell edge, mm
  const Eigen::Array3i& dims() const { return dims_; }

  static constexpr double kMaxCells = 4194304.0;  ///< 2^22, as TriangleGrid

 private:
  Eigen::Vector3d origin_ = Eigen::Vector3d::Zero();
  double cell_ = 1.0;
  Eigen::Array3i dims_ = Eigen::Array3i::Ones();
  std::vector<std::int64_t> start_ = {0, 0};  ///< cell c's items: list_[start_[c] .. start_[c + 1])
  std::vector<int> list_;
};

}  // namespace tissuemesh
