#include "surface/surface_quality.h"

#include "surface/triangle_geometry.h"

#include <algorithm>
#include <cmath>

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

bool improves_table1_minima(const SurfaceQuality& before, const SurfaceQuality& after) {
  return after.min_angle_deg >= before.min_angle_deg && after.q_min >= before.q_min &&
         (after.min_angle_deg > before.min_angle_deg || after.q_min > before.q_min ||
          after.p30_percent < before.p30_percent);
}

}  // namespace tissuemesh
