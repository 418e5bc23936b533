#include "mesher/surface_distance.h"

#include <algorithm>

namespace tissuemesh {
namespace {

double max_distance(const TriSurface& from, const SurfaceProjection& to) {
  double d = 0.0;
  for (const Eigen::Vector3d& p : from.points) d = std::max(d, to.distance(p));
  for (const std::array<int, 3>& t : from.triangles) {
    const Eigen::Vector3d &a = from.points[t[0]], &b = from.points[t[1]], &c = from.points[t[2]];
    d = std::max({d, to.distance((a + b + c) / 3.0), to.distance(0.5 * (a + b)), to.distance(0.5 * (b + c)),
                  to.distance(0.5 * (c + a))});
  }
  return d;
}

}  // namespace

SurfaceDistance hausdorff_distance(const TriSurface& a, const SurfaceProjection& a_on, const TriSurface& b,
                                   const SurfaceProjection& b_on) {
  SurfaceDistance d;
  d.a_to_b_mm = max_distance(a, b_on);
  d.b_to_a_mm = max_distance(b, a_on);
  return d;
}

}  // namespace tissuemesh
