// FreeCellGrid: a uniform grid over a triangle surface's bounding box whose cells that no triangle
// touches ("free" cells) are grouped into face-connected components. Every point of a component
// lies in the same region of the surface's partition of space, so one inside/outside query per
// component answers it for all of its points, and a segment whose bounding box covers only free
// cells meets no triangle. Used by the volume mesher's domain (volume/free_cell_domain.h).
//
// Conservative: a cell that a triangle meets is always touched (a cell marked touched that no
// triangle meets only costs a slower query). Deterministic: components are numbered in x-fastest
// scan order of their first cell.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <array>
#include <cstddef>
#include <vector>

namespace tissuemesh {

class FreeCellGrid {
 public:
  /// Grid of cubic cells of edge `cell_mm` (> 0) over the bounding box of `points` (the vertices
  /// of `triangles`) with a border of one cell on each side, so the cells outside the box stay free
  /// where no triangle is; the cell grows (by 1.25 at a time) until the grid fits `max_cells`. An
  /// empty or non-finite input, or max_cells 0, gives an empty grid that answers nothing.
  FreeCellGrid(const std::vector<Eigen::Vector3d>& points, const std::vector<std::array<int, 3>>& triangles,
               double cell_mm, std::size_t max_cells = 16u << 20);

  /// Component of the free cell holding `x`, or -1 when that cell is touched or `x` is outside
  /// the grid (or not finite).
  int component(const Eigen::Vector3d& x) const;
  /// True when every cell that the bounding box of segment [a, b] overlaps is free, so that no
  /// triangle meets the segment; false otherwise (also when the box leaves the grid or spans more
  /// than `max_cells` cells, which are not worth scanning).
  bool segment_is_free(const Eigen::Vector3d& a, const Eigen::Vector3d& b, long max_cells = 512) const;
  /// The closed box of the grid cell holding `x`; empty when `x` is outside the grid.
  Eigen::AlignedBox3d cell_box(const Eigen::Vector3d& x) const;
  std::size_t components() const { return seeds_.size(); }
  /// The centre of the first cell (scan order) of component `c`: a point to classify it by.
  const Eigen::Vector3d& seed(std::size_t c) const { return seeds_[c]; }
  double cell_mm() const { return cell_; }
  /// Share of the grid's cells that are free (0..1; a diagnostic).
  double free_share() const { return free_share_; }

 private:
  /// Position of cell (i, j, k) in component_ (x fastest).
  std::size_t index(long i, long j, long k) const {
    return static_cast<std::size_t>((k * dims_[1] + j) * dims_[0] + i);
  }
  /// The cell holding `x` in `ijk`; false when the grid is empty or `x` is outside it (or NaN).
  bool cell_of(const Eigen::Vector3d& x, std::array<long, 3>& ijk) const;

  Eigen::Vector3d origin_;
  double cell_ = 1.0;
  std::array<long, 3> dims_{};
  std::vector<int> component_;  ///< per cell (x fastest): -1 touched, else the component
  std::vector<Eigen::Vector3d> seeds_;
  double free_share_ = 0;
};

}  // namespace tissuemesh
