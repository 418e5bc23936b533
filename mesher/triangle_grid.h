// TriangleGrid: a uniform hash grid of triangle bounding boxes, for finding the triangles near a
// box (the remesher's intersection guard, mesher/remesh_complex.h).
//
// Entries are never removed: a triangle that changed is inserted again with its new box, and a
// query returns every id entered in a cell the box touches, with repeats and stale entries; the
// caller filters by the current geometry. Rebuild (clear and insert all) now and then to drop the
// stale ones. Deterministic: results come in cell order, then insertion order.
#pragma once

#include <Eigen/Geometry>

#include <cstdint>
#include <unordered_map>
#include <vector>

namespace tissuemesh {

class TriangleGrid {
 public:
  /// Empties the grid and sets the cell edge (mm, > 0).
  void reset(double cell_mm);
  void insert(int id, const Eigen::AlignedBox3d& box);
  /// Appends to `out` the ids entered in the cells `box` touches.
  void query(const Eigen::AlignedBox3d& box, std::vector<int>& out) const;

 private:
  std::uint64_t key(int i, int j, int k) const;
  Eigen::Vector3i cell_of(const Eigen::Vector3d& p) const;

  double inverse_cell_ = 1.0;
  std::unordered_map<std::uint64_t, std::vector<int>> cells_;
};

}  // namespace tissuemesh
