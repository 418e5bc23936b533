#include "mesher/triangle_intersection.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/intersections.h>

namespace tissuemesh {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;

Point point(const Eigen::Vector3d& p) { return Point(p[0], p[1], p[2]); }

Kernel::Triangle_3 triangle(const TrianglePoints& t) { return {point(t[0]), point(t[1]), point(t[2])}; }

}  // namespace

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
  if (shared == 0) return CGAL::do_intersect(triangle(a), triangle(b));
  if (shared == 1) {
    int i = 0;
    while (in_b[i] < 0) ++i;
    const int j = in_b[i];
    const Kernel::Segment_3 opposite_a(point(a[(i + 1) % 3]), point(a[(i + 2) % 3]));
    const Kernel::Segment_3 opposite_b(point(b[(j + 1) % 3]), point(b[(j + 2) % 3]));
    return CGAL::do_intersect(opposite_a, triangle(b)) || CGAL::do_intersect(opposite_b, triangle(a));
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
