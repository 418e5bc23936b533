#include "workflows/label_transfer.h"

#include "core/errors.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace tissuemesh {

namespace {

/// Barycentric slack for a voxel centre on a tet face (round-off of the 3x3 solve).
constexpr double kInsideSlack = 1e-10;

}  // namespace

LabelImage transfer_labels(const LabelImage& labels, const Model& model, const std::vector<Eigen::Vector3d>& undeformed,
                           const std::vector<Eigen::Vector3d>& deformed) {
  if (undeformed.size() != model.nodes.size() || deformed.size() != model.nodes.size())
    throw std::invalid_argument("transfer_labels: one position per model node in each configuration");
  const Eigen::Matrix3d M = labels.index_to_physical();
  const Eigen::Matrix3d M_inv = M.inverse();
  // The deformed corners in the input's continuous index frame (relative to its origin).
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(INFINITY), hi = -lo;
  for (int v = 0; v < model.num_corner_nodes; ++v) {
    const Eigen::Vector3d ijk = M_inv * (deformed[v] - labels.origin);
    lo = lo.cwiseMin(ijk);
    hi = hi.cwiseMax(ijk);
  }
  LabelImage out;
  out.spacing = labels.spacing;
  out.direction = labels.direction;
  Eigen::Vector3d first;
  double voxels = 1.0;
  for (int a = 0; a < 3; ++a) {
    first[a] = std::floor(lo[a]) - 1.0;
    const double n = std::ceil(hi[a]) + 1.0 - first[a] + 1.0;
    voxels *= n;
    out.dims[a] = static_cast<int>(std::min(n, 2e9));
  }
  if (!(voxels < 2147483648.0))
    throw InputError("the supine label image would need " + std::to_string(voxels) +
                     " voxels at the input spacing (the deformed mesh reaches far outside the input image)");
  out.origin = labels.origin + M * first;
  out.labels.assign(out.voxel_count(), 0);
  std::vector<char> set(out.voxel_count(), 0);

  auto nearest_label = [&](const Eigen::Vector3d& p) -> std::int32_t {
    const Eigen::Vector3d ijk = M_inv * (p - labels.origin);
    int idx[3];
    for (int a = 0; a < 3; ++a) {
      idx[a] = static_cast<int>(std::lround(ijk[a]));
      if (idx[a] < 0 || idx[a] >= labels.dims[a]) return 0;
    }
    return labels.at(idx[0], idx[1], idx[2]);
  };

  for (const auto& el : model.elements) {
    // Corners in the output grid's index frame.
    Eigen::Vector3d c[4];
    for (int k = 0; k < 4; ++k) c[k] = M_inv * (deformed[el[k]] - out.origin);
    Eigen::Matrix3d A;
    A << c[1] - c[0], c[2] - c[0], c[3] - c[0];
    const Eigen::PartialPivLU<Eigen::Matrix3d> lu(A);
    if (!(std::abs(A.determinant()) > 0.0)) continue;  // a flat deformed tet covers no voxel centre
    int from[3], to[3];
    for (int a = 0; a < 3; ++a) {
      const double mn = std::min({c[0][a], c[1][a], c[2][a], c[3][a]});
      const double mx = std::max({c[0][a], c[1][a], c[2][a], c[3][a]});
      from[a] = std::max(0, static_cast<int>(std::ceil(mn - 1e-9)));
      to[a] = std::min(out.dims[a] - 1, static_cast<int>(std::floor(mx + 1e-9)));
    }
    for (int k = from[2]; k <= to[2]; ++k)
      for (int j = from[1]; j <= to[1]; ++j)
        for (int i = from[0]; i <= to[0]; ++i) {
          const std::size_t at = out.index(i, j, k);
          if (set[at]) continue;
          const Eigen::Vector3d l = lu.solve(Eigen::Vector3d(i, j, k) - c[0]);
          const double l0 = 1.0 - l.sum();
          if (std::min({l0, l[0], l[1], l[2]}) < -kInsideSlack) continue;
          const Eigen::Vector3d p = l0 * undeformed[el[0]] + l[0] * undeformed[el[1]] + l[1] * undeformed[el[2]] +
                                    l[2] * undeformed[el[3]];
          out.labels[at] = nearest_label(p);
          set[at] = 1;
        }
  }
  return out;
}

}  // namespace tissuemesh
