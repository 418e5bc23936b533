// TriangleGrid: a uniform grid of triangle bounding boxes over a fixed region, for finding the
// triangles near a box (the remesher's intersection guard, surface/remesh_complex.h).
//
// Each id is entered in every cell its box touches; entering an id again first takes it out of
// the cells of its previous box (nothing changes when the new box touches the same cells), and
// remove() takes it out entirely, so a query sees each live id in the cells of its current box
// only. A query returns the ids of the cells the box touches
// (an id spanning several of them more than once); the caller tests the actual boxes.
// The cells are one dense array over the region given to reset(); a box reaching beyond it is
// entered in (and a query beyond it reads) the border cells, so nothing is ever missed, only
// found among more candidates. Because every cell exists from reset() on, calls that touch
// disjoint sets of cells (and distinct ids) may run on different threads at once (the remesher's
// partitioned sweeps); anything else must not overlap.
// Deterministic for a deterministic sequence of calls.
#pragma once

#include <Eigen/Geometry>

#include <cstddef>
#include <vector>

namespace tissuemesh {

class TriangleGrid {
 public:
  /// Empties the grid and covers `region` with cells of edge `cell_mm` (> 0), made larger if the
  /// region would otherwise need more than kMaxCells cells.
  void reset(double cell_mm, const Eigen::AlignedBox3d& region);
  /// Enters id (>= 0) with `box`, replacing its previous entry.
  void insert(int id, const Eigen::AlignedBox3d& box);
  void remove(int id);
  /// Appends to `out` the ids entered in the cells `box` touches.
  void query(const Eigen::AlignedBox3d& box, std::vector<int>& out) const;
  /// The cell edge in force (mm): the one asked for, or larger (reset()).
  double cell() const { return 1.0 / inverse_cell_; }
  /// Index along axis `axis` (0, 1, 2) of the cell holding coordinate `c` on that axis (clamped to
  /// the region's cells).
  int slab_of(double c, int axis) const;

  /// 2^22 cells (~100 MB of empty cells at most).
  static constexpr std::size_t kMaxCells = std::size_t(1) << 22;

 private:
  struct Range {
    Eigen::Vector3i lo, hi;
    bool present = false;
  };
  Eigen::Vector3i cell_of(const Eigen::Vector3d& p) const;
  std::size_t index(int i, int j, int k) const { return (static_cast<std::size_t>(k) * dims_[1] + j) * dims_[0] + i; }

  double inverse_cell_ = 1.0;
  Eigen::Vector3i origin_ = Eigen::Vector3i::Zero();  ///< absolute index of the first cell per axis
  Eigen::Vector3i dims_ = Eigen::Vector3i::Zero();
  std::vector<std::vector<int>> cells_;
  std::vector<Range> range_;  ///< per id: the cells it is entered in
};

}  // namespace tissuemesh
