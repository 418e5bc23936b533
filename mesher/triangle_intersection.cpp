#include "mesher/triangle_intersection.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/intersections.h>

namespace tissuemesh {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;

Point point(const Eigen::Vector3d& p) { return Point(p[0], p[1], p[2]); }

Kernel::Triangle_3 triangle(const TrianglePoints& t) { return {point(t[0]), point(t[1]), point(t[2])}; }

/// True when p and q lie strictly on the same side of the plane of t (exact): the segment pq then
/// cannot meet t. A cheap exact rejection before CGAL's general segment and triangle tests.
bool strictly_one_side(const Kernel::Triangle_3& t, const Point& p, const Point& q) {
  const CGAL::Orientation a = CGAL::orientation(t[0], t[1], t[2], p);
  return a != CGAL::COPLANAR && a == CGAL::orientation(t[0], t[1], t[2], q);
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
  const Kernel::Triangle_3 ta = triangle(a), tb = triangle(b);
  if (shared == 0) {
    if (strictly_one_side(ta, tb[0], tb[1]) && strictly_one_side(ta, tb[1], tb[2])) return false;
    return CGAL::do_intersect(ta, tb);
  }
  if (shared == 1) {
    int i = 0;
    while (in_b[i] < 0) ++i;
    const int j = in_b[i];
    const Point a1 = ta[(i + 1) % 3], a2 = ta[(i + 2) % 3], b1 = tb[(j + 1) % 3], b2 = tb[(j + 2) % 3];
    const bool a_clear = strictly_one_side(tb, a1, a2) || !CGAL::do_intersect(Kernel::Segment_3(a1, a2), tb);
    return !a_clear || !(strictly_one_side(ta, b1, b2) || !CGAL::do_intersect(Kernel::Segment_3(b1, b2), ta));
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
