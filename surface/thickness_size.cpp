#include "surface/thickness_size.h"

#include "core/errors.h"
#include "image/local_thickness.h"

#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <limits>

namespace tissuemesh {

ThicknessSize::ThicknessSize(const LabelImage& ids, double cap_mm, double ratio, double floor_mm)
    : dims_(ids.dims), origin_(ids.origin), to_index_(ids.index_to_physical().inverse()) {
  if (!(cap_mm > 0.0) || !(ratio > 0.0) || !(floor_mm > 0.0) || !std::isfinite(cap_mm) || !std::isfinite(ratio) ||
      !std::isfinite(floor_mm))
    throw InputError("thickness sizing: the thickness cap, the edge/thickness ratio and the smallest edge must be > 0");
  bound_ = local_thickness(ids, cap_mm);
  for (std::size_t v = 0; v < bound_.size(); ++v) {
    float& b = bound_[v];
    // Outside (id 0) is not meshed: a thin band of air or of ignored labels bounds nothing.
    if (ids.labels[v] == 0) b = std::numeric_limits<float>::infinity();
    if (!std::isfinite(b)) continue;
    ++thin_voxels_;
    b = static_cast<float>(std::max(ratio * b, floor_mm));
  }
}

double ThicknessSize::operator()(const Eigen::Vector3d& p) const {
  const Eigen::Vector3d ijk = to_index_ * (p - origin_);
  double best = std::numeric_limits<double>::infinity();
  const int i0 = static_cast<int>(std::floor(ijk[0])), j0 = static_cast<int>(std::floor(ijk[1])),
            k0 = static_cast<int>(std::floor(ijk[2]));
  for (int dk = 0; dk < 2; ++dk)
    for (int dj = 0; dj < 2; ++dj)
      for (int di = 0; di < 2; ++di) {
        const int i = i0 + di, j = j0 + dj, k = k0 + dk;
        if (i < 0 || j < 0 || k < 0 || i >= dims_[0] || j >= dims_[1] || k >= dims_[2]) continue;
        best = std::min(best, static_cast<double>(
                                  bound_[static_cast<std::size_t>(i) +
                                         static_cast<std::size_t>(dims_[0]) *
                                             (static_cast<std::size_t>(j) + static_cast<std::size_t>(dims_[1]) * k)]));
      }
  return best;
}

}  // namespace tissuemesh
