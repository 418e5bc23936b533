#include "surface/surface_quality.h"

#include "surface/triangle_geometry.h"

#include "core/face_key.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

namespace tissuemesh {

SurfaceQuality surface_quality(const TriSurface& s) {
  SurfaceQuality q;
  q.triangles = s.triangles.size();
  if (s.triangles.empty()) return q;
  constexpr double kDeg = 180.0 / EIGEN_PI;
  q.min_angle_deg = 180.0;
  q.q_min = 1.0;
  std::size_t below30 = 0;
  double sum_min = 0.0, sum_q = 0.0, sum_edge = 0.0;
  for (const auto& t : s.triangles) {
    const Eigen::Vector3d &a = s.points[t[0]], &b = s.points[t[1]], &c = s.points[t[2]];
    const std::array<double, 3> angles = triangle_angles(a, b, c);  // zero for a zero-area triangle
    const double min_angle = std::min({angles[0], angles[1], angles[2]}) * kDeg;
    for (double angle : angles) below30 += angle * kDeg < 30.0;
    const double quality = triangle_quality(a, b, c);
    sum_min += min_angle;
    sum_q += quality;
    sum_edge += ((b - c).norm() + (c - a).norm() + (a - b).norm()) / 3.0;
    q.min_angle_deg = std::min(q.min_angle_deg, min_angle);
    q.q_min = std::min(q.q_min, quality);
  }
  const double n = static_cast<double>(s.triangles.size());
  q.average_min_angle_deg = sum_min / n;
  q.p30_percent = 100.0 * static_cast<double>(below30) / (3.0 * n);
  q.q_average = sum_q / n;
  q.mean_edge_mm = sum_edge / n;
  return q;
}

double sharpest_fold_deg(const TriSurface& s) {
  std::vector<std::pair<std::uint64_t, int>> uses;  // (edge_key, triangle), sorted: an edge's uses in a row
  uses.reserve(3 * s.triangles.size());
  for (std::size_t t = 0; t < s.triangles.size(); ++t)
    for (int e = 0; e < 3; ++e)
      uses.emplace_back(edge_key(s.triangles[t][e], s.triangles[t][(e + 1) % 3]), static_cast<int>(t));
  std::sort(uses.begin(), uses.end());
  auto normal = [&](int t) {
    const auto& w = s.triangles[t];
    return area_vector(s.points[w[0]], s.points[w[1]], s.points[w[2]]);
  };
  double sharpest = 180.0;
  for (std::size_t i = 0; i < uses.size();) {
    std::size_t j = i;
    while (j < uses.size() && uses[j].first == uses[i].first) ++j;
    const int a = uses[i].second, b = j - i == 2 ? uses[i + 1].second : -1;
    if (b >= 0 && s.labels[a] == s.labels[b]) {
      const Eigen::Vector3d na = normal(a), nb = normal(b);
      if (na.norm() > 0.0 && nb.norm() > 0.0) {
        // Triangles of one patch are oriented alike: coplanar normals agree (180 degrees between
        // the triangles), a flat fold turns one normal over (0 degrees).
        const double turn = std::atan2(na.cross(nb).norm(), na.dot(nb));
        sharpest = std::min(sharpest, 180.0 - turn * (180.0 / M_PI));
      }
    }
    i = j;
  }
  return sharpest;
}

bool improves_table1_minima(const SurfaceQuality& before, const SurfaceQuality& after) {
  return after.min_angle_deg >= before.min_angle_deg && after.q_min >= before.q_min &&
         (after.min_angle_deg > before.min_angle_deg || after.q_min > before.q_min ||
          after.p30_percent < before.p30_percent);
}

}  // namespace tissuemesh
