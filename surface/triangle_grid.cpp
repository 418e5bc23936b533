#include "surface/triangle_grid.h"

#include <algorithm>
#include <cassert>
#include <cmath>

namespace tissuemesh {
namespace {

int absolute_index(double x, double inverse_cell) { return static_cast<int>(std::floor(x * inverse_cell)); }

}  // namespace

void TriangleGrid::reset(double cell_mm, const Eigen::AlignedBox3d& region) {
  assert(cell_mm > 0.0 && !region.isEmpty());
  // Grow the cell until the region fits in kMaxCells (a huge image with tiny triangles): queries
  // then return more candidates, never fewer.
  for (;;) {
    inverse_cell_ = 1.0 / cell_mm;
    for (int a = 0; a < 3; ++a) {
      origin_[a] = absolute_index(region.min()[a], inverse_cell_);
      dims_[a] = absolute_index(region.max()[a], inverse_cell_) - origin_[a] + 1;
    }
    if (static_cast<double>(dims_[0]) * dims_[1] * dims_[2] <= static_cast<double>(kMaxCells)) break;
    cell_mm *= 1.25;
  }
  cells_.assign(static_cast<std::size_t>(dims_[0]) * dims_[1] * dims_[2], {});
  range_.clear();
}

Eigen::Vector3i TriangleGrid::cell_of(const Eigen::Vector3d& p) const {
  Eigen::Vector3i c;
  for (int a = 0; a < 3; ++a) c[a] = std::clamp(absolute_index(p[a], inverse_cell_) - origin_[a], 0, dims_[a] - 1);
  return c;
}

int TriangleGrid::slab_of(double c, int axis) const {
  return std::clamp(absolute_index(c, inverse_cell_) - origin_[axis], 0, dims_[axis] - 1);
}

void TriangleGrid::remove(int id) {
  if (id >= static_cast<int>(range_.size()) || !range_[id].present) return;
  const Range& r = range_[id];
  for (int k = r.lo[2]; k <= r.hi[2]; ++k)
    for (int j = r.lo[1]; j <= r.hi[1]; ++j)
      for (int i = r.lo[0]; i <= r.hi[0]; ++i) {
        std::vector<int>& cell = cells_[index(i, j, k)];
        cell.erase(std::find(cell.begin(), cell.end(), id));
      }
  range_[id].present = false;
}

void TriangleGrid::insert(int id, const Eigen::AlignedBox3d& box) {
  const Eigen::Vector3i lo = cell_of(box.min()), hi = cell_of(box.max());
  if (id < static_cast<int>(range_.size()) && range_[id].present && range_[id].lo == lo && range_[id].hi == hi)
    return;  // the same cells: nothing to change (most moves are small)
  remove(id);
  if (id >= static_cast<int>(range_.size())) range_.resize(id + 1);
  Range& r = range_[id];
  r.lo = lo;
  r.hi = hi;
  r.present = true;
  for (int k = r.lo[2]; k <= r.hi[2]; ++k)
    for (int j = r.lo[1]; j <= r.hi[1]; ++j)
      for (int i = r.lo[0]; i <= r.hi[0]; ++i) cells_[index(i, j, k)].push_back(id);
}

void TriangleGrid::query(const Eigen::AlignedBox3d& box, std::vector<int>& out) const {
  const Eigen::Vector3i lo = cell_of(box.min()), hi = cell_of(box.max());
  for (int k = lo[2]; k <= hi[2]; ++k)
    for (int j = lo[1]; j <= hi[1]; ++j)
      for (int i = lo[0]; i <= hi[0]; ++i) {
        const std::vector<int>& cell = cells_[index(i, j, k)];
        out.insert(out.end(), cell.begin(), cell.end());
      }
}

}  // namespace tissuemesh
