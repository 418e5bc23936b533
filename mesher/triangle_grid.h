// TriangleGrid: a uniform hash grid of triangle bounding boxes, for finding the triangles near a
// box (the remesher's intersection guard, mesher/remesh_complex.h).
//
// Each id is entered in every cell its box touches; entering an id again first takes it out of
// the cells of its previous box (nothing changes when the new box touches the same cells), and
// remove() takes it out entirely, so a query sees each live id in the cells of its current box
// only. A query returns the ids of the cells the box touches
// (an id spanning several of them more than once); the caller tests the actual boxes.
// Deterministic for a deterministic sequence of calls.
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
  /// Enters id (>= 0) with `box`, replacing its previous entry.
  void insert(int id, const Eigen::AlignedBox3d& box);
  void remove(int id);
  /// Appends to `out` the ids entered in the cells `box` touches.
  void query(const Eigen::AlignedBox3d& box, std::vector<int>& out) const;

 private:
  struct Range {
    Eigen::Vector3i lo, hi;
    bool present = false;
  };
  static std::uint64_t key(int i, int j, int k);
  Eigen::Vector3i cell_of(const Eigen::Vector3d& p) const;

  double inverse_cell_ = 1.0;
  std::unordered_map<std::uint64_t, std::vector<int>> cells_;
  std::vector<Range> range_;  ///< per id: the cells it is entered in
};

}  // namespace tissuemesh
