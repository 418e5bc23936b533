#include "mesher/triangle_grid.h"

#include <cmath>

namespace tissuemesh {

void TriangleGrid::reset(double cell_mm) {
  inverse_cell_ = 1.0 / cell_mm;
  cells_.clear();
}

std::uint64_t TriangleGrid::key(int i, int j, int k) const {
  // 21 bits per axis, offset to stay positive: +-1M cells, far beyond any image.
  constexpr std::int64_t kOffset = 1 << 20;
  return (static_cast<std::uint64_t>(i + kOffset) << 42) | (static_cast<std::uint64_t>(j + kOffset) << 21) |
         static_cast<std::uint64_t>(k + kOffset);
}

Eigen::Vector3i TriangleGrid::cell_of(const Eigen::Vector3d& p) const {
  return {static_cast<int>(std::floor(p[0] * inverse_cell_)), static_cast<int>(std::floor(p[1] * inverse_cell_)),
          static_cast<int>(std::floor(p[2] * inverse_cell_))};
}

void TriangleGrid::insert(int id, const Eigen::AlignedBox3d& box) {
  const Eigen::Vector3i lo = cell_of(box.min()), hi = cell_of(box.max());
  for (int i = lo[0]; i <= hi[0]; ++i)
    for (int j = lo[1]; j <= hi[1]; ++j)
      for (int k = lo[2]; k <= hi[2]; ++k) cells_[key(i, j, k)].push_back(id);
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
