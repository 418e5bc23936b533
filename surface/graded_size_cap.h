// GradedSizeCap: a graded upper bound on the remesher's size field around "stuck" edges, which it
// cannot bring to size (kept short by fixed junction corners or by the guards of
// surface/remesh_complex.h). Near a stuck edge of length l (mm) with midpoint m the size is at most
//   cap(x) = factor * l + gradation * |x - m|
// i.e. the size an isosceles triangle on that edge needs for its apex angle to reach
// 2 asin(1 / (2 factor)) (30 degrees at factor 1.93), growing back linearly (a Lipschitz bound, so
// the size does not jump) to the size field elsewhere. The cap over several edges is the minimum
// of theirs. Deterministic; queries are O(1) on average (a grid of each edge's influence box) and
// may run on several threads at once (add() must not overlap them).
#pragma once

#include "surface/triangle_grid.h"

#include <Eigen/Geometry>

#include <vector>

namespace tissuemesh {

class GradedSizeCap {
 public:
  /// `factor` (> 0) and `gradation` (> 0, mm per mm) as in the header comment; `region`: where
  /// the queries will be (mm; outside it they are still right, only slower).
  GradedSizeCap(double factor, double gradation, const Eigen::AlignedBox3d& region);

  /// Adds a stuck edge with midpoint `m` and length `length` (mm). Its cap only matters where it is
  /// below `largest` (mm, the largest size the field can ask for), so it is entered only within
  /// (largest - factor * length) / gradation of m; nothing is entered when that is not positive.
  void add(const Eigen::Vector3d& m, double length, double largest);
  /// The cap at p (mm): the minimum over the added edges, +infinity where none reaches.
  double operator()(const Eigen::Vector3d& p) const;
  std::size_t size() const { return seeds_.size(); }

 private:
  struct Seed {
    Eigen::Vector3d m;
    double size;  ///< factor * length, mm
  };
  double factor_, gradation_;
  Eigen::AlignedBox3d region_;
  std::vector<Seed> seeds_;
  TriangleGrid grid_;  ///< seed ids by influence box
  double cell_ = 0.0;  ///< grid cell (mm), fixed at the first add()
};

}  // namespace tissuemesh
