#include "mesher/forced_radius_edge.h"

#include "mesher/triangle_geometry.h"

#include <cmath>

namespace tissuemesh {

ForcedRadiusEdge forced_radius_edge_ratio(const TriSurface& surface, double bound) {
  surface.validate("surface for the forced radius-edge ratio");
  ForcedRadiusEdge forced;
  for (std::size_t t = 0; t < surface.triangles.size(); ++t) {
    const auto& k = surface.triangles[t];
    // min_angle is exact to round-off for every shape (atan2) and 0 for a zero-area triangle,
    // whose bound is then 1 / 0 = +infinity.
    const double theta = min_angle(surface.points[k[0]], surface.points[k[1]], surface.points[k[2]]);
    const double ratio = 1.0 / (2.0 * std::sin(theta));
    if (ratio > bound) ++forced.triangles_above_bound;
    if (forced.triangle < 0 || ratio > forced.ratio) {
      forced.ratio = ratio;
      forced.triangle = static_cast<int>(t);
      forced.min_angle_deg = theta * 180.0 / EIGEN_PI;
    }
  }
  return forced;
}

}  // namespace tissuemesh
