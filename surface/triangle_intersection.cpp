#include "surface/triangle_intersection.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/intersections.h>

#include <cmath>

namespace tissuemesh {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;

Point point(const Eigen::Vector3d& p) { return Point(p[0], p[1], p[2]); }

/// True when segment pq meets the closed triangle t (exact).
bool segment_meets(const Eigen::Vector3d& p, const Eigen::Vector3d& q, const TrianglePoints& t) {
  return CGAL::do_intersect(Kernel::Segment_3(point(p), point(q)), Kernel::Triangle_3(point(t[0]), point(t[1]), point(t[2])));
}

/// Shewchuk's bound holds without underflow: every component used must be 0 or at least this
/// (so that products of three stay normal doubles); else the exact predicate decides. Coordinates
/// in mm never come near it.
constexpr double kSmallestFiltered = 0x1p-300;

bool filterable(const Eigen::Vector3d& v) {
  for (int i = 0; i < 3; ++i)
    if (v[i] != 0.0 && std::abs(v[i]) < kSmallestFiltered) return false;
  return true;
}

}  // namespace

bool triangle_is_degenerate(const TrianglePoints& t) { return CGAL::collinear(point(t[0]), point(t[1]), point(t[2])); }

PreparedTriangle::PreparedTriangle(const TrianglePoints& t) : t_(t) {
  const Eigen::Vector3d a = t[1] - t[0], b = t[2] - t[0];
  normal_ = {a.y() * b.z() - a.z() * b.y(), a.z() * b.x() - a.x() * b.z(), a.x() * b.y() - a.y() * b.x()};
  magnitude_ = {std::abs(a.y() * b.z()) + std::abs(a.z() * b.y()), std::abs(a.z() * b.x()) + std::abs(a.x() * b.z()),
                std::abs(a.x() * b.y()) + std::abs(a.y() * b.x())};
  filterable_ = filterable(a) && filterable(b);
}

int PreparedTriangle::side(const Eigen::Vector3d& p) const {
  // Shewchuk (1997): orient3d evaluated in doubles is off by at most (7 + 56 u) u times the
  // permanent (u = 2^-53) when nothing underflows; doubled for margin. An infinite or NaN bound
  // (overflow) fails both comparisons and falls through to the exact predicate.
  constexpr double kErrorBound = 2.0 * (7.0 + 56.0 * 0x1p-53) * 0x1p-53;
  const Eigen::Vector3d c = p - t_[0];
  if (filterable_ && filterable(c)) {
    const double det = c.dot(normal_);
    const double bound = kErrorBound * c.cwiseAbs().dot(magnitude_);
    if (det > bound) return 1;
    if (det < -bound) return -1;
  }
  return static_cast<int>(CGAL::orientation(point(t_[0]), point(t_[1]), point(t_[2]), point(p)));
}

bool PreparedTriangle::strictly_one_side(const Eigen::Vector3d& p, const Eigen::Vector3d& q) const {
  const int a = side(p);
  return a != 0 && a == side(q);
}

bool triangles_intersect(const TrianglePoints& a, const std::array<int, 3>& ia, const TrianglePoints& b,
                         const std::array<int, 3>& ib) {
  return triangles_intersect(PreparedTriangle(a), ia, PreparedTriangle(b), ib);
}

bool triangles_intersect(const PreparedTriangle& prepared_a, const std::array<int, 3>& ia,
                         const PreparedTriangle& prepared_b, const std::array<int, 3>& ib) {
  const TrianglePoints &a = prepared_a.points(), &b = prepared_b.points();
  // Position in b of each vertex of a (-1: not shared).
  std::array<int, 3> in_b{-1, -1, -1};
  int shared = 0;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      if (ia[i] == ib[j]) {
        in_b[i] = j;
        ++shared;
      }
  if (shared == 3) return true;
  if (shared == 0) {
    if (prepared_a.strictly_one_side(b[0], b[1]) && prepared_a.strictly_one_side(b[1], b[2])) return false;
    return CGAL::do_intersect(Kernel::Triangle_3(point(a[0]), point(a[1]), point(a[2])),
                              Kernel::Triangle_3(point(b[0]), point(b[1]), point(b[2])));
  }
  if (shared == 1) {
    int i = 0;
    while (in_b[i] < 0) ++i;
    const int j = in_b[i];
    const Eigen::Vector3d &a1 = a[(i + 1) % 3], &a2 = a[(i + 2) % 3], &b1 = b[(j + 1) % 3], &b2 = b[(j + 2) % 3];
    // When a1 and a2 lie strictly on one side of b's plane, a meets that plane only in the shared
    // vertex, so neither a1a2 nor b1b2 (in b's plane, not through b's own vertex: b is not
    // degenerate, or its plane would have no strict side) can meet the other triangle; the same
    // with a and b swapped. Only when neither holds are the two edges tested.
    if (prepared_b.strictly_one_side(a1, a2) || prepared_a.strictly_one_side(b1, b2)) return false;
    return segment_meets(a1, a2, b) || segment_meets(b1, b2, a);
  }
  // A shared edge (p, q); r and s the other vertices.
  int i = 0;
  while (in_b[i] >= 0) ++i;
  int j = 0;
  while (j == in_b[(i + 1) % 3] || j == in_b[(i + 2) % 3]) ++j;
  const Point p = point(a[(i + 1) % 3]), q = point(a[(i + 2) % 3]), r = point(a[i]), s = point(b[j]);
  return CGAL::coplanar(p, q, r, s) && CGAL::coplanar_orientation(p, q, r, s) == CGAL::POSITIVE;
}

}  // namespace tissuemesh
