// Why: the remesher projects over a million points onto an extracted surface of hundreds of
// thousands of triangles, all of them within a few triangle sizes of the surface. So a query
// searches the cells around the point in growing shells and stops once the closest point found is
// nearer than anything outside the cells searched, and computes closest points only for triangles
// whose box is nearer than the best so far.
#include "surface/patch_grid.h"

#include "surface/triangle_geometry.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <utility>

namespace tissuemesh {
namespace {

using Eigen::Array3i;
using Eigen::Vector3d;

/// Cell edge over the mean triangle extent (largest box side): a query near the surface finds its
/// closest point among the 27 cells around it, most of them skipped by their distance (not tuned).
constexpr double kCellPerExtent = 2.0;

/// Squared distance from p to the box [lo, hi] (0 inside).
double box_distance2(const Vector3d& p, const Vector3d& lo, const Vector3d& hi) {
  return (lo - p).cwiseMax(p - hi).cwiseMax(0.0).squaredNorm();
}

/// The lower (upper) corners of the triangles' boxes.
std::vector<Vector3d> box_corners(const std::vector<std::array<Vector3d, 3>>& triangles, bool upper) {
  std::vector<Vector3d> out;
  out.reserve(triangles.size());
  for (const auto& q : triangles)
    out.push_back(upper ? q[0].cwiseMax(q[1]).cwiseMax(q[2]).eval() : q[0].cwiseMin(q[1]).cwiseMin(q[2]).eval());
  return out;
}

}  // namespace

PatchGrid::PatchGrid(std::vector<std::array<Vector3d, 3>> triangles, std::vector<int> patch)
    : triangles_(std::move(triangles)),
      patch_(std::move(patch)),
      lo_(box_corners(triangles_, false)),
      hi_(box_corners(triangles_, true)),
      grid_(lo_, hi_, {}, kCellPerExtent) {
  if (patch_.size() != triangles_.size() || std::any_of(patch_.begin(), patch_.end(), [](int k) { return k < 0; }))
    throw std::invalid_argument("PatchGrid: one patch id >= 0 per triangle expected");
  for (int k : patch_) {
    if (k >= static_cast<int>(patch_triangles_.size())) patch_triangles_.resize(static_cast<std::size_t>(k) + 1, 0);
    ++patch_triangles_[static_cast<std::size_t>(k)];
  }
}

PatchGrid::Hit PatchGrid::closest(int patch, const Vector3d& p) const {
  if (patch < 0 || patch >= static_cast<int>(patch_triangles_.size()) || patch_triangles_[static_cast<std::size_t>(patch)] == 0)
    return Hit{};
  return search(patch, p, -1);
}

PatchGrid::Hit PatchGrid::closest_any(const Vector3d& p, int max_shells) const {
  if (triangles_.empty()) return Hit{};
  return search(-1, p, max_shells);
}

PatchGrid::Hit PatchGrid::search(int patch, const Vector3d& p, int max_shells) const {
  Hit best;
  if (!p.allFinite()) return best;
  double best2 = std::numeric_limits<double>::infinity();
  auto visit = [&](int i, int j, int k) {
    const double cell = grid_.cell();
    const Vector3d cell_lo = grid_.origin() + cell * Vector3d(i, j, k);
    // Nothing nearer in it (while nothing is found, every cell is searched: a distance can
    // overflow to infinity for a point very far away).
    if (best.triangle >= 0 && box_distance2(p, cell_lo, cell_lo + Vector3d::Constant(cell)) >= best2) return;
    const std::int64_t c = grid_.index(Array3i(i, j, k));
    for (const int* e = grid_.begin(c); e != grid_.end(c); ++e) {
      const int t = *e;
      if ((patch >= 0 && patch_[static_cast<std::size_t>(t)] != patch) ||
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
  const Array3i c0 = grid_.cell_of(p), dims = grid_.dims();
  const Vector3d& origin = grid_.origin();
  const double cell = grid_.cell();
  for (int r = 0;; ++r) {
    // Shell r: the cells at Chebyshev distance r from c0 (inside the grid).
    const Array3i lo = (c0 - r).max(0), hi = (c0 + r).min(dims - 1);
    for (int k = lo[2]; k <= hi[2]; ++k)
      for (int j = lo[1]; j <= hi[1]; ++j) {
        if (std::abs(k - c0[2]) == r || std::abs(j - c0[1]) == r) {
          for (int i = lo[0]; i <= hi[0]; ++i) visit(i, j, k);
        } else {
          if (c0[0] - r >= 0) visit(c0[0] - r, j, k);
          if (c0[0] + r < dims[0]) visit(c0[0] + r, j, k);
        }
      }
    // Every point outside the cells searched so far is at least `bound` away from p (a side of
    // the block at the grid's border has nothing beyond it).
    double bound = std::numeric_limits<double>::infinity();
    for (int a = 0; a < 3; ++a) {
      if (c0[a] - r > 0) bound = std::min(bound, p[a] - (origin[a] + (c0[a] - r) * cell));
      if (c0[a] + r < dims[a] - 1) bound = std::min(bound, origin[a] + (c0[a] + r + 1) * cell - p[a]);
    }
    if (bound == std::numeric_limits<double>::infinity() || (best.triangle >= 0 && best2 <= bound * bound)) break;
    if (max_shells >= 0 && r >= max_shells) return Hit{};
  }
  return best;
}

}  // namespace tissuemesh
