#include "surface/box_grid.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>

namespace tissuemesh {

BoxGrid::BoxGrid(const std::vector<Eigen::Vector3d>& lo, const std::vector<Eigen::Vector3d>& hi,
                 const std::vector<char>& entered, double cell_per_extent) {
  const std::size_t n = lo.size();
  auto in = [&](std::size_t i) { return entered.empty() || entered[i]; };
  Eigen::AlignedBox3d bounds;
  double extent = 0.0;
  std::size_t count = 0;
  for (std::size_t i = 0; i < n; ++i)
    if (in(i)) {
      bounds.extend(lo[i]).extend(hi[i]);
      extent += (hi[i] - lo[i]).maxCoeff();
      ++count;
    }
  if (count == 0) return;  // one empty cell
  origin_ = bounds.min();
  cell_ = std::max(cell_per_extent * extent / static_cast<double>(count), 1e-9);
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
  auto for_cells = [&](std::size_t i, auto f) {
    const Eigen::Array3i a = cell_of(lo[i]), b = cell_of(hi[i]);
    for (int k = a[2]; k <= b[2]; ++k)
      for (int j = a[1]; j <= b[1]; ++j)
        for (int l = a[0]; l <= b[0]; ++l) f(static_cast<std::size_t>(index(Eigen::Array3i(l, j, k))));
  };
  for (std::size_t i = 0; i < n; ++i)
    if (in(i)) for_cells(i, [&](std::size_t c) { ++start_[c + 1]; });
  for (std::size_t c = 0; c < cells; ++c) start_[c + 1] += start_[c];
  list_.resize(static_cast<std::size_t>(start_[cells]));
  std::vector<std::int64_t> fill(start_.begin(), start_.end() - 1);
  for (std::size_t i = 0; i < n; ++i)
    if (in(i)) for_cells(i, [&](std::size_t c) { list_[static_cast<std::size_t>(fill[c]++)] = static_cast<int>(i); });
}

Eigen::Array3i BoxGrid::cell_of(const Eigen::Vector3d& p) const {
  Eigen::Array3i c;
  for (int a = 0; a < 3; ++a) {
    const double x = std::floor((p[a] - origin_[a]) / cell_);
    c[a] = x > 0.0 ? static_cast<int>(std::min(x, static_cast<double>(dims_[a] - 1))) : 0;
  }
  return c;
}

}  // namespace tissuemesh
