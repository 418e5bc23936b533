// Why: two face-adjacent free cells form a box that no triangle meets, so a component lies in one
// region. A cell is marked touched when the triangle's bounding box meets the cell grown by a
// margin (a thousandth of the cell, far above rounding) and the cell's corners are not all
// strictly on one side of the triangle's plane (grown by the same margin): the margin keeps
// points near a cell's faces safe against rounding. A needle or nearly flat triangle, whose
// computed normal is unreliable, marks its whole box.
#include "volume/free_cell_grid.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>

namespace tissuemesh {

namespace {
constexpr int kTouched = -1;
constexpr int kUnvisited = -2;
}  // namespace

FreeCellGrid::FreeCellGrid(const std::vector<Eigen::Vector3d>& points,
                           const std::vector<std::array<int, 3>>& triangles, double cell_mm, std::size_t max_cells)
    : origin_(Eigen::Vector3d::Zero()), cell_(cell_mm) {
  if (points.empty() || triangles.empty() || !(cell_mm > 0) || max_cells == 0) return;
  Eigen::AlignedBox3d box;
  for (const auto& p : points) box.extend(p);
  if (!box.sizes().allFinite()) return;
  // Cells per axis for the box with a one-cell border on each side; the cell grows until the
  // grid fits max_cells (counted in doubles, so a tiny cell cannot overflow the count).
  auto cells_per_axis = [&](int a) { return std::ceil(box.sizes()[a] / cell_) + 2.0; };
  while (cells_per_axis(0) * cells_per_axis(1) * cells_per_axis(2) > static_cast<double>(max_cells)) cell_ *= 1.25;
  for (int a = 0; a < 3; ++a) dims_[a] = static_cast<long>(cells_per_axis(a));
  origin_ = box.min() - Eigen::Vector3d::Constant(cell_);
  component_.assign(static_cast<std::size_t>(dims_[0] * dims_[1] * dims_[2]), kUnvisited);

  // A margin far above rounding (coordinates of a few hundred mm carry ~1e-13 mm of error) and
  // far below the cell, so marking stays conservative at no measurable cost in free cells.
  const double margin = 1e-3 * cell_;
  const double half = 0.5 * cell_ + margin;
  for (const auto& t : triangles) {
    const Eigen::Vector3d& a = points[t[0]];
    const Eigen::Vector3d& b = points[t[1]];
    const Eigen::Vector3d& c = points[t[2]];
    const Eigen::Vector3d lo = a.cwiseMin(b).cwiseMin(c) - origin_ - Eigen::Vector3d::Constant(margin);
    const Eigen::Vector3d hi = a.cwiseMax(b).cwiseMax(c) - origin_ + Eigen::Vector3d::Constant(margin);
    std::array<long, 3> i0{}, i1{};
    for (int d = 0; d < 3; ++d) {
      i0[d] = static_cast<long>(std::clamp(std::floor(lo[d] / cell_), 0.0, static_cast<double>(dims_[d] - 1)));
      i1[d] = static_cast<long>(std::clamp(std::floor(hi[d] / cell_), 0.0, static_cast<double>(dims_[d] - 1)));
    }
    // The plane test needs a trustworthy normal: for a needle or nearly flat triangle the cross
    // product is mostly rounding and points anywhere, so such a triangle marks its whole box.
    Eigen::Vector3d n = (b - a).cross(c - a);
    const double length = n.norm();
    const bool has_plane = length > 1e-6 * (b - a).norm() * (c - a).norm() && std::isfinite(length);
    if (has_plane) n /= length;
    // Projection radius of a grown cell on the normal: beyond it, all eight corners are strictly
    // on one side of the plane and the cell cannot meet the triangle.
    const double reach = half * n.cwiseAbs().sum() + margin;
    for (long k = i0[2]; k <= i1[2]; ++k)
      for (long j = i0[1]; j <= i1[1]; ++j)
        for (long i = i0[0]; i <= i1[0]; ++i) {
          if (has_plane) {
            const Eigen::Vector3d centre = origin_ + cell_ * Eigen::Vector3d(i + 0.5, j + 0.5, k + 0.5);
            if (std::abs(n.dot(centre - a)) > reach) continue;
          }
          component_[index(i, j, k)] = kTouched;
        }
  }

  // Face-connected flood fill over the free cells, in scan order.
  std::vector<std::size_t> stack;
  std::size_t free = 0;
  const std::array<std::size_t, 3> stride{1, static_cast<std::size_t>(dims_[0]),
                                          static_cast<std::size_t>(dims_[0] * dims_[1])};
  for (long k = 0; k < dims_[2]; ++k)
    for (long j = 0; j < dims_[1]; ++j)
      for (long i = 0; i < dims_[0]; ++i) {
        if (component_[index(i, j, k)] != kUnvisited) continue;
        const int id = static_cast<int>(seeds_.size());
        seeds_.push_back(origin_ + cell_ * Eigen::Vector3d(i + 0.5, j + 0.5, k + 0.5));
        component_[index(i, j, k)] = id;
        stack.push_back(index(i, j, k));
        while (!stack.empty()) {
          const std::size_t cell = stack.back();
          stack.pop_back();
          ++free;
          const std::array<long, 3> at{static_cast<long>(cell % stride[1]),
                                       static_cast<long>((cell / stride[1]) % static_cast<std::size_t>(dims_[1])),
                                       static_cast<long>(cell / stride[2])};
          for (int d = 0; d < 3; ++d) {
            if (at[d] > 0 && component_[cell - stride[d]] == kUnvisited) {
              component_[cell - stride[d]] = id;
              stack.push_back(cell - stride[d]);
            }
            if (at[d] + 1 < dims_[d] && component_[cell + stride[d]] == kUnvisited) {
              component_[cell + stride[d]] = id;
              stack.push_back(cell + stride[d]);
            }
          }
        }
      }
  free_share_ = static_cast<double>(free) / static_cast<double>(component_.size());
}

bool FreeCellGrid::cell_of(const Eigen::Vector3d& x, std::array<long, 3>& ijk) const {
  if (component_.empty()) return false;
  for (int d = 0; d < 3; ++d) {
    const double u = std::floor((x[d] - origin_[d]) / cell_);
    if (!(u >= 0 && u < static_cast<double>(dims_[d]))) return false;  // also catches NaN
    ijk[d] = static_cast<long>(u);
  }
  return true;
}

int FreeCellGrid::component(const Eigen::Vector3d& x) const {
  std::array<long, 3> ijk{};
  return cell_of(x, ijk) ? component_[index(ijk[0], ijk[1], ijk[2])] : kTouched;
}

Eigen::AlignedBox3d FreeCellGrid::cell_box(const Eigen::Vector3d& x) const {
  std::array<long, 3> ijk{};
  if (!cell_of(x, ijk)) return {};
  const Eigen::Vector3d lo = origin_ + cell_ * Eigen::Vector3d(ijk[0], ijk[1], ijk[2]);
  return {lo, lo + Eigen::Vector3d::Constant(cell_)};
}

bool FreeCellGrid::segment_is_free(const Eigen::Vector3d& a, const Eigen::Vector3d& b, long max_cells) const {
  std::array<long, 3> lo{}, hi{};
  if (!cell_of(a.cwiseMin(b), lo) || !cell_of(a.cwiseMax(b), hi)) return false;
  if ((hi[0] - lo[0] + 1) * (hi[1] - lo[1] + 1) * (hi[2] - lo[2] + 1) > max_cells) return false;
  for (long k = lo[2]; k <= hi[2]; ++k)
    for (long j = lo[1]; j <= hi[1]; ++j)
      for (long i = lo[0]; i <= hi[0]; ++i)
        if (component_[index(i, j, k)] < 0) return false;
  return true;
}

}  // namespace tissuemesh
