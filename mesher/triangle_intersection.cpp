#include "mesher/triangle_intersection.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/intersections.h>

#include <cmath>

namespace tissuemesh {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;

Point point(const Eigen::Vector3d& p) { return Point(p[0], p[1], p[2]); }

/// The plane through (t0, t1, t2), prepared for exact side tests of many points: the sign of
/// det[t1 - t0, t2 - t0, p - t0] (CGAL::orientation(t0, t1, t2, p)) is taken from double
/// arithmetic when Shewchuk's (1997) forward error bound for orient3d, (7 + 56 u) u times the
/// permanent (u = 2^-53), doubled for margin, proves it, else from CGAL's exact predicate. The
/// answers are CGAL's in every case; most cost one dot product with the precomputed normal.
class PlaneSide {
 public:
  PlaneSide(const Eigen::Vector3d& t0, const Eigen::Vector3d& t1, const Eigen::Vector3d& t2) : t0_(t0), t1_(t1), t2_(t2) {
    const Eigen::Vector3d a = t1 - t0, b = t2 - t0;
    normal_ = {a.y() * b.z() - a.z() * b.y(), a.z() * b.x() - a.x() * b.z(), a.x() * b.y() - a.y() * b.x()};
    magnitude_ = {std::abs(a.y() * b.z()) + std::abs(a.z() * b.y()), std::abs(a.z() * b.x()) + std::abs(a.x() * b.z()),
                  std::abs(a.x() * b.y()) + std::abs(a.y() * b.x())};
  }
  CGAL::Orientation side(const Eigen::Vector3d& p) const {
    const Eigen::Vector3d c = p - t0_;
    const double det = c.dot(normal_);
    const double bound = kErrorBound * c.cwiseAbs().dot(magnitude_);
    if (det > bound) return CGAL::POSITIVE;
    if (det < -bound) return CGAL::NEGATIVE;
    return CGAL::orientation(point(t0_), point(t1_), point(t2_), point(p));
  }
  /// True when p and q lie strictly on the same side (exact): the segment pq then misses the plane.
  bool strictly_one_side(const Eigen::Vector3d& p, const Eigen::Vector3d& q) const {
    const CGAL::Orientation a = side(p);
    return a != CGAL::COPLANAR && a == side(q);
  }

 private:
  static constexpr double kErrorBound = 2.0 * (7.0 + 56.0 * 0x1p-53) * 0x1p-53;
  Eigen::Vector3d t0_, t1_, t2_, normal_, magnitude_;
};

/// True when segment pq meets the closed triangle t (exact), the one-side rejection first.
bool segment_meets(const Eigen::Vector3d& p, const Eigen::Vector3d& q, const PlaneSide& plane, const TrianglePoints& t) {
  return !plane.strictly_one_side(p, q) &&
         CGAL::do_intersect(Kernel::Segment_3(point(p), point(q)), Kernel::Triangle_3(point(t[0]), point(t[1]), point(t[2])));
}

}  // namespace

bool triangle_is_degenerate(const TrianglePoints& t) { return CGAL::collinear(point(t[0]), point(t[1]), point(t[2])); }

bool triangles_intersect(const TrianglePoints& a, const std::array<int, 3>& ia, const TrianglePoints& b,
                         const std::array<int, 3>& ib) {
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
    const PlaneSide plane(a[0], a[1], a[2]);
    if (plane.strictly_one_side(b[0], b[1]) && plane.strictly_one_side(b[1], b[2])) return false;
    return CGAL::do_intersect(Kernel::Triangle_3(point(a[0]), point(a[1]), point(a[2])),
                              Kernel::Triangle_3(point(b[0]), point(b[1]), point(b[2])));
  }
  if (shared == 1) {
    int i = 0;
    while (in_b[i] < 0) ++i;
    const int j = in_b[i];
    return segment_meets(a[(i + 1) % 3], a[(i + 2) % 3], PlaneSide(b[0], b[1], b[2]), b) ||
           segment_meets(b[(j + 1) % 3], b[(j + 2) % 3], PlaneSide(a[0], a[1], a[2]), a);
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
