// PatchGrid: closest points on the patches of a triangle surface through one uniform grid of
// triangle boxes (surface/box_grid.h; SurfaceProjection's patch queries, surface/surface_projection.h).
//
// A query returns the closest point of the patch up to round-off (point-triangle closest points
// in double precision, surface/triangle_geometry.h), the first found among equally close
// triangles, in a fixed order: deterministic. Queries are const and may run from several threads.
#pragma once

#include "surface/box_grid.h"

#include <Eigen/Core>

#include <array>
#include <limits>
#include <vector>

namespace tissuemesh {

class PatchGrid {
 public:
  /// `triangles` (corner points, mm) with their patch ids in `patch` (0 .. patches - 1; one per
  /// triangle, else std::invalid_argument).
  PatchGrid(std::vector<std::array<Eigen::Vector3d, 3>> triangles, std::vector<int> patch);

  struct Hit {
    Eigen::Vector3d point = Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN());  ///< closest point, mm
    int triangle = -1;  ///< index into the constructor's triangles (-1: none found, point NaN)
  };
  /// Closest point of patch `patch` to p; none (triangle -1) for a patch without triangles or a
  /// non-finite p.
  Hit closest(int patch, const Eigen::Vector3d& p) const;
  /// Closest point of any patch to p; none for a grid without triangles or a non-finite p. With
  /// `max_shells` >= 0 also none when the search would go past that many shells of cells around
  /// p's (0: its own cell only) before it knows the closest point: the cells grow with the
  /// triangles, and far from small triangles a tree of their boxes is faster.
  Hit closest_any(const Eigen::Vector3d& p, int max_shells = -1) const;

 private:
  /// closest() over the triangles of `patch`, or of every patch for -1, at most `max_shells`
  /// shells (-1: no bound).
  Hit search(int patch, const Eigen::Vector3d& p, int max_shells) const;
  std::vector<std::array<Eigen::Vector3d, 3>> triangles_;
  std::vector<int> patch_;
  std::vector<Eigen::Vector3d> lo_, hi_;  ///< per triangle: its box
  std::vector<int> patch_triangles_;      ///< per patch: how many triangles it has
  BoxGrid grid_;                          ///< of the triangles' boxes
};

}  // namespace tissuemesh
