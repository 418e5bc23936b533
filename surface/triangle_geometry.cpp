#include "surface/triangle_geometry.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>

namespace tissuemesh {

using Eigen::Vector3d;

Vector3d area_vector(const Vector3d& a, const Vector3d& b, const Vector3d& c) { return 0.5 * (b - a).cross(c - a); }

std::array<double, 3> triangle_angles(const Vector3d& a, const Vector3d& b, const Vector3d& c) {
  const double twice_area = 2.0 * area_vector(a, b, c).norm();
  if (!(twice_area > 0.0)) return {0.0, 0.0, 0.0};
  return {std::atan2(twice_area, (b - a).dot(c - a)), std::atan2(twice_area, (a - b).dot(c - b)),
          std::atan2(twice_area, (a - c).dot(b - c))};
}

double angle_at_c(const Vector3d& a, const Vector3d& b, const Vector3d& c) {
  const double twice_area = 2.0 * area_vector(a, b, c).norm();
  return twice_area > 0.0 ? std::atan2(twice_area, (a - c).dot(b - c)) : 0.0;
}

double min_angle(const Vector3d& a, const Vector3d& b, const Vector3d& c) {
  // atan2(y, x) falls as x grows for a fixed y > 0, so the smallest angle is the one with the
  // largest dot product: one atan2 instead of three (the remesher asks this millions of times).
  const double twice_area = 2.0 * area_vector(a, b, c).norm();
  if (!(twice_area > 0.0)) return 0.0;
  return std::atan2(twice_area, std::max({(b - a).dot(c - a), (a - b).dot(c - b), (a - c).dot(b - c)}));
}

double triangle_quality(const Vector3d& a, const Vector3d& b, const Vector3d& c) {
  const double la = (b - c).norm(), lb = (c - a).norm(), lc = (a - b).norm();
  const double area = area_vector(a, b, c).norm();
  const double p = 0.5 * (la + lb + lc), h = std::max({la, lb, lc});
  return p > 0.0 && h > 0.0 ? 6.0 / std::sqrt(3.0) * area / (p * h) : 0.0;
}

Vector3d closest_point_on_triangle(const Vector3d& p, const Vector3d& a, const Vector3d& b, const Vector3d& c) {
  const Vector3d ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return a;
  const Vector3d bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return b;
  // The edge cases divide by a squared edge length (d1 - d3 = |ab|^2, and so on), the interior by
  // twice the squared area: zero only for a degenerate triangle, handled apart below.
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0 && d1 - d3 > 0) return a + d1 / (d1 - d3) * ab;
  const Vector3d cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0 && d2 - d6 > 0) return a + d2 / (d2 - d6) * ac;
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0 && (d4 - d3) + (d5 - d6) > 0)
    return b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b);
  if (!(va + vb + vc > 0)) {
    // Collinear or coincident corners: the triangle is its edges; the nearest of their closest points.
    auto on_segment = [&p](const Vector3d& u, const Vector3d& w) {
      const Vector3d uw = w - u;
      const double len2 = uw.squaredNorm();
      return len2 > 0 ? Vector3d(u + std::clamp((p - u).dot(uw) / len2, 0.0, 1.0) * uw) : u;
    };
    Vector3d best = on_segment(a, b);
    for (const Vector3d& q : {on_segment(b, c), on_segment(c, a)})
      if ((p - q).squaredNorm() < (p - best).squaredNorm()) best = q;
    return best;
  }
  const double denom = 1.0 / (va + vb + vc);
  return a + ab * (vb * denom) + ac * (vc * denom);
}

double point_triangle_distance(const Vector3d& p, const Vector3d& a, const Vector3d& b, const Vector3d& c) {
  return (p - closest_point_on_triangle(p, a, b, c)).norm();
}

}  // namespace tissuemesh
