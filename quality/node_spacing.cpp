#include "quality/node_spacing.h"

#include "quality/mesh_quality.h"

#include <algorithm>
#include <cmath>

namespace tissuemesh {

std::vector<double> largest_incident_circumradius_mm(const TetMesh& mesh) {
  std::vector<double> radius(mesh.points.size(), 0.0);
  for (const auto& t : mesh.tets) {
    const double r = tet_shape(mesh.points[t[0]], mesh.points[t[1]], mesh.points[t[2]], mesh.points[t[3]]).circumradius_mm;
    if (!std::isfinite(r)) continue;  // a flat tet has no size to give
    for (int v : t) radius[v] = std::max(radius[v], r);
  }
  return radius;
}

}  // namespace tissuemesh
