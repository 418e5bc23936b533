#include "mesher/patch_grid.h"

#include "mesher/triangle_geometry.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace tissuemesh {
namespace {

using Eigen::Array3i;
using Eigen::Vector3d;

/// Cell edge over the mean triangle extent (largest box side): a query near the surface finds its
/// closest point among the 27 cells around it, most of them skipped by their distance (not tuned).
constexpr double kCellPerExtent = 2.0;
/// At most this many cells (the cell grows until the surface's box fits).
constexpr double kMaxCells = 4194304.0;

/// Squared distance from p to the box [lo, hi] (0 inside).
double box_distance2(const Vector3d& p, const Vector3d& lo, const Vector3d& hi) {
  return (lo - p).cwiseMax(p - hi).cwiseMax(0.0).squaredNorm();
}

}  // namespace

PatchGrid::PatchGrid(const std::vector<std::array<Vector3d, 3>>& triangles, const std::vector<int>& patch)
    : triangles_(triangles), patch_(patch) {
  if (patch_.size() != triangles_.size() || std::any_of(patch_.begin(), patch_.end(), [](int k) { return k < 0; }))
    throw std::invalid_argument("PatchGrid: one patch id >= 0 per triangle expected");
  const std::size_t n = triangles_.size();
  lo_.resize(n);
  hi_.resize(n);
  Eigen::AlignedBox3d bounds;
  double extent = 0.0;
  for (std::size_t t = 0; t < n; ++t) {
    const auto& q = triangles_[t];
    lo_[t] = q[0].cwiseMin(q[1]).cwiseMin(q[2]);
    hi_[t] = q[0].cwiseMax(q[1]).cwiseMax(q[2]);
    bounds.extend(lo_[t]).extend(hi_[t]);
    extent += (hi_[t] - lo_[t]).maxCoeff();
    const int k = patch_[t];
    if (k >= static_cast<int>(patch_triangles_.size())) patch_triangles_.resize(static_cast<std::size_t>(k) + 1, 0);
    ++patch_triangles_[static_cast<std::size_t>(k)];
  }
  if (n == 0) return;
  origin_ = bounds.min();
  cell_ = std::max(kCellPerExtent * extent / static_cast<double>(n), 1e-9);
  for (;;) {  // in double first: a tiny cell must not overflow int
    const Eigen::Array3d d = ((bounds.max() - bounds.min()).array() / cell_).floor() + 1.0;
    if (d.prod() <= kMaxCells) {
      dims_ = d.cast<int>();
      break;
    }
    cell_ *= 1.25;
  }
  const std::size_t cells = static_cast<std::size_t>(dims_[0]) * dims_[1] * dims_[2];
  start_.assign(cells + 1, 0);
  auto for_cells = [&](std::size_t t, auto f) {
    const Array3i lo = cell_of(lo_[t]), hi = cell_of(hi_[t]);
    for (int k = lo[2]; k <= hi[2]; ++k)
      for (int j = lo[1]; j <= hi[1]; ++j)
        for (int i = lo[0]; i <= hi[0]; ++i) f(index(Array3i(i, j, k)));
  };
  for (std::size_t t = 0; t < n; ++t) for_cells(t, [&](std::int64_t c) { ++start_[static_cast<std::size_t>(c) + 1]; });
  for (std::size_t c = 0; c < cells; ++c) start_[c + 1] += start_[c];
  list_.resize(static_cast<std::size_t>(start_[cells]));
  std::vector<std::int64_t> fill(start_.begin(), start_.end() - 1);
  for (std::size_t t = 0; t < n; ++t)
    for_cells(t, [&](std::int64_t c) { list_[static_cast<std::size_t>(fill[static_cast<std::size_t>(c)]++)] = static_cast<int>(t); });
}

Array3i PatchGrid::cell_of(const Vector3d& p) const {
  // Clamped in double (a point far outside, or NaN, must not overflow int).
  Array3i c;
  for (int a = 0; a < 3; ++a) {
    const double x = std::floor((p[a] - origin_[a]) / cell_);
    c[a] = x > 0.0 ? static_cast<int>(std::min(x, static_cast<double>(dims_[a] - 1))) : 0;
  }
  return c;
}

PatchGrid::Hit PatchGrid::closest(int patch, const Vector3d& p) const {
  Hit best;
  if (patch < 0 || patch >= static_cast<int>(patch_triangles_.size()) || patch_triangles_[static_cast<std::size_t>(patch)] == 0 ||
      !p.allFinite())
    return best;
  double best2 = std::numeric_limits<double>::infinity();
  auto visit = [&](int i, int j, int k) {
    const Vector3d cell_lo = origin_ + cell_ * Vector3d(i, j, k);
    // Nothing nearer in it (while nothing is found, every cell is searched: a distance can
    // overflow to infinity for a point very far away).
    if (best.triangle >= 0 && box_distance2(p, cell_lo, cell_lo + Vector3d::Constant(cell_)) >= best2) return;
    const std::int64_t c = index(Array3i(i, j, k));
    for (std::int64_t e = start_[static_cast<std::size_t>(c)]; e < start_[static_cast<std::size_t>(c) + 1]; ++e) {
      const int t = list_[static_cast<std::size_t>(e)];
      if (patch_[static_cast<std::size_t>(t)] != patch ||
          (best.triangle >= 0 && box_distance2(p, lo_[static_cast<std::size_t>(t)], hi_[static_cast<std::size_t>(t)]) >= best2))
        continue;
      const auto& q = triangles_[static_cast<std::size_t>(t)];
      const Vector3d x = closest_point_on_triangle(p, q[0], q[1], q[2]);
      const double d2 = (p - x).squaredNorm();
      if (best.triangle < 0 || d2 < best2) {
        best2 = d2;
        best.point = x;
        best.triangle = t;
      }
    }
  };
  const Array3i c0 = cell_of(p);
  for (int r = 0;; ++r) {
    // Shell r: the cells at Chebyshev distance r from c0 (inside the grid).
    const Array3i lo = (c0 - r).max(0), hi = (c0 + r).min(dims_ - 1);
    for (int k = lo[2]; k <= hi[2]; ++k)
      for (int j = lo[1]; j <= hi[1]; ++j) {
        if (std::abs(k - c0[2]) == r || std::abs(j - c0[1]) == r) {
          for (int i = lo[0]; i <= hi[0]; ++i) visit(i, j, k);
        } else {
          if (c0[0] - r >= 0) visit(c0[0] - r, j, k);
          if (c0[0] + r < dims_[0]) visit(c0[0] + r, j, k);
        }
      }
    // Every point outside the cells searched so far is at least `bound` away from p (a side of
    // the block at the grid's border has nothing beyond it).
    double bound = std::numeric_limits<double>::infinity();
    for (int a = 0; a < 3; ++a) {
      if (c0[a] - r > 0) bound = std::min(bound, p[a] - (origin_[a] + (c0[a] - r) * cell_));
      if (c0[a] + r < dims_[a] - 1) bound = std::min(bound, origin_[a] + (c0[a] + r + 1) * cell_ - p[a]);
    }
    if (bound == std::numeric_limits<double>::infinity() || (best.triangle >= 0 && best2 <= bound * bound)) break;
  }
  return best;
}

}  // namespace tissuemesh
