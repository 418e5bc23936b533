#include "core/label_image.h"

#include "core/errors.h"

#include <cmath>
#include <sstream>

namespace tissuemesh {

std::map<std::int32_t, std::size_t> LabelImage::label_counts() const {
  std::map<std::int32_t, std::size_t> counts;
  // Labels are usually a handful of values: count runs to avoid a map lookup per voxel.
  std::size_t n = labels.size();
  std::size_t start = 0;
  while (start < n) {
    std::size_t end = start + 1;
    while (end < n && labels[end] == labels[start]) ++end;
    counts[labels[start]] += end - start;
    start = end;
  }
  return counts;
}

void LabelImage::validate(const std::string& what) const {
  std::ostringstream err;
  if (dims[0] <= 0 || dims[1] <= 0 || dims[2] <= 0) {
    err << what << ": image dimensions " << dims[0] << " x " << dims[1] << " x " << dims[2]
        << " are not all positive";
  } else if (labels.size() != voxel_count()) {
    err << what << ": holds " << labels.size() << " voxels, dimensions say " << voxel_count();
  } else if (!(spacing.array() > 0.0).all() || !spacing.allFinite()) {
    err << what << ": voxel spacing (" << spacing.transpose() << ") mm must be positive";
  } else if (!direction.allFinite() ||
             !(direction.transpose() * direction).isIdentity(1e-4)) {
    err << what << ": orientation (direction) matrix is not orthonormal";
  }
  if (!err.str().empty()) throw InputError(err.str());
}

std::string orientation_code(const Eigen::Matrix3d& direction) {
  static const char pos[3] = {'L', 'P', 'S'};
  static const char neg[3] = {'R', 'A', 'I'};
  std::string code;
  for (int c = 0; c < 3; ++c) {
    Eigen::Index row = 0;
    direction.col(c).cwiseAbs().maxCoeff(&row);
    code += direction(row, c) >= 0 ? pos[row] : neg[row];
  }
  return code;
}

}  // namespace tissuemesh
