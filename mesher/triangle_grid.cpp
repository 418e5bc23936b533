#include "mesher/triangle_grid.h"

#include <algorithm>
#include <cmath>

namespace tissuemesh {

void TriangleGrid::reset(double cell_mm) {
  inverse_cell_ = 1.0 / cell_mm;
  cells_.clear();
  range_.clear();
}

std::uint64_t TriangleGrid::key(int i, int j, int k) {
  // 21 bits per axis, offset to stay positive: +-1M cells, far beyond any image.
  constexpr std::int64_t kOffset = 1 << 20;
  return (static_cast<std::uint64_t>(i + kOffset) << 42) | (static_cast<std::uint64_t>(j + kOffset) << 21) |
         static_cast<std::uint64_t>(k + kOffset);
}

Eigen::Vector3i TriangleGrid::cell_of(const Eigen::Vector3d& p) const {
  return {static_cast<int>(std::floor(p[0] * inverse_cell_)), static_cast<int>(std::floor(p[1] * inverse_cell_)),
          static_cast<int>(std::floor(p[2] * inverse_cell_))};
}

void TriangleGrid::remove(int id) {
  if (id >= static_cast<int>(range_.size()) || !range_[id].present) return;
  const Range& r = range_[id];
  for (int i = r.lo[0]; i <= r.hi[0]; ++i)
    for (int j = r.lo[1]; j <= r.hi[1]; ++j)
      for (int k = r.lo[2]; k <= r.hi[2]; ++k) {
        std::vector<int>& cell = cells_[key(i, j, k)];
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
  for (int i = r.lo[0]; i <= r.hi[0]; ++i)
    for (int j = r.lo[1]; j <= r.hi[1]; ++j)
      for (int k = r.lo[2]; k <= r.hi[2]; ++k) cells_[key(i, j, k)].push_back(id);
}

void TriangleGrid::query(const Eigen::AlignedBox3d& box, std::vector<int>& out) const {
  const Eigen::Vector3i lo = cell_of(box.min()), hi = cell_of(box.max());
  for (int i = lo[0]; i <= hi[0]; ++i)
    for (int j = lo[1]; j <= hi[1]; ++j)
      for (int k = lo[2]; k <= hi[2]; ++k) {
        const auto it = cells_.find(key(i, j, k));
        if (it != cells_.end()) out.insert(out.end(), it->second.begin(), it->second.end());
      }
}

}  // namespace tissuemesh
