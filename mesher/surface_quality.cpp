#include "mesher/surface_quality.h"

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
    const double la = (b - c).norm(), lb = (c - a).norm(), lc = (a - b).norm();  // opposite a, b, c
    const double area = 0.5 * (b - a).cross(c - a).norm();
    const double p = 0.5 * (la + lb + lc), h = std::max({la, lb, lc});
    double min_angle = 0.0;
    if (area > 0.0) {
      // Angle opposite each edge from atan2(2A, adjacent dot product): accurate for all shapes.
      const double angles[3] = {std::atan2(2.0 * area, (b - a).dot(c - a)), std::atan2(2.0 * area, (a - b).dot(c - b)),
                                std::atan2(2.0 * area, (a - c).dot(b - c))};
      min_angle = std::min({angles[0], angles[1], angles[2]}) * kDeg;
      for (double angle : angles) below30 += angle * kDeg < 30.0;
    } else {
      below30 += 3;
    }
    const double quality = p > 0.0 && h > 0.0 ? 6.0 / std::sqrt(3.0) * area / (p * h) : 0.0;
    sum_min += min_angle;
    sum_q += quality;
    sum_edge += (la + lb + lc) / 3.0;
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

}  // namespace tissuemesh
