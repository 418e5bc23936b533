// Why the bound holds: let T be a triangle with smallest angle theta and shortest edge l (the edge
// opposite theta). By the law of sines its circumradius is r = l / (2 sin theta). A tet with T as
// a face has a circumsphere through T's three corners, so its circumradius R >= r, and its
// shortest edge is at most l; hence R / shortest edge >= 1 / (2 sin theta).
//
// Why unforced tets are counted by surface nodes: TetGen -Y's unforced tets span thin layers
// between surface nodes. The likely reason (not checked here): TetGen 1.5 splits a bad tet at its
// circumcentre and rejects that point when it encroaches a triangle -Y keeps (or, with -m, a
// vertex's protecting ball), and inside a thin layer it nearly always does.
#include "volume/forced_radius_edge.h"

#include "core/errors.h"
#include "core/face_key.h"
#include "quality/mesh_quality.h"
#include "surface/triangle_geometry.h"

#include <array>
#include <cmath>
#include <map>
#include <string>
#include <unordered_set>

namespace tissuemesh {

namespace {

/// Smallest interior angle of surface triangle t, radians: exact to round-off for every shape
/// (atan2) and 0 for a zero-area triangle.
double smallest_angle(const TriSurface& surface, std::size_t t) {
  const auto& k = surface.triangles[t];
  return min_angle(surface.points[k[0]], surface.points[k[1]], surface.points[k[2]]);
}

/// The header comment's bound for a triangle with smallest angle theta: +infinity when theta = 0.
double forced_ratio(double theta) { return 1.0 / (2.0 * std::sin(theta)); }

}  // namespace

ForcedRadiusEdge forced_radius_edge_ratio(const TriSurface& surface, double bound) {
  surface.validate("surface for the forced radius-edge ratio");
  ForcedRadiusEdge forced;
  for (std::size_t t = 0; t < surface.triangles.size(); ++t) {
    const double theta = smallest_angle(surface, t);
    const double ratio = forced_ratio(theta);
    if (ratio > bound) ++forced.triangles_above_bound;
    if (forced.triangle < 0 || ratio > forced.ratio) {
      forced.ratio = ratio;
      forced.triangle = static_cast<int>(t);
      forced.min_angle_deg = theta * 180.0 / EIGEN_PI;
    }
  }
  return forced;
}

RadiusEdgeAccount account_radius_edge_above(const TetMesh& mesh, const TriSurface& surface, double bound) {
  surface.validate("surface for the radius-edge account");
  mesh.validate("mesh for the radius-edge account");
  if (mesh.points.size() >= kMaxFaceKeyNodes)
    throw InputError("mesh for the radius-edge account has " + std::to_string(mesh.points.size()) +
                     " nodes; at most " + std::to_string(kMaxFaceKeyNodes - 1) + " are supported");
  // Mesh node of every surface point (-1: none), by exact coordinates.
  std::map<std::array<double, 3>, int> node_at;
  for (std::size_t v = 0; v < mesh.points.size(); ++v)
    node_at.emplace(std::array<double, 3>{mesh.points[v].x(), mesh.points[v].y(), mesh.points[v].z()},
                    static_cast<int>(v));
  std::vector<int> node_of_point(surface.points.size(), -1);
  for (std::size_t i = 0; i < surface.points.size(); ++i) {
    const auto it = node_at.find({surface.points[i].x(), surface.points[i].y(), surface.points[i].z()});
    if (it != node_at.end()) node_of_point[i] = it->second;
  }
  std::vector<char> on_surface(mesh.points.size(), 0);  // a node that is a corner of a surface triangle
  for (const auto& k : surface.triangles)
    for (int i : k)
      if (node_of_point[i] >= 0) on_surface[node_of_point[i]] = 1;
  std::unordered_set<std::uint64_t> forcing_faces;
  for (std::size_t t = 0; t < surface.triangles.size(); ++t) {
    const auto& k = surface.triangles[t];
    const int a = node_of_point[k[0]], b = node_of_point[k[1]], c = node_of_point[k[2]];
    if (a >= 0 && b >= 0 && c >= 0 && forced_ratio(smallest_angle(surface, t)) > bound) forcing_faces.insert(face_key(a, b, c));
  }
  RadiusEdgeAccount account;
  for (std::size_t i = 0; i < mesh.tets.size(); ++i) {
    const auto& t = mesh.tets[i];
    const double ratio =
        tet_shape(mesh.points[t[0]], mesh.points[t[1]], mesh.points[t[2]], mesh.points[t[3]]).radius_edge_ratio;
    if (!(ratio > bound)) continue;  // a flat tet's +infinity counts
    ++account.above;
    bool forced = false;
    for (int q = 0; q < 4 && !forced; ++q)
      forced = forcing_faces.count(face_key(t[(q + 1) % 4], t[(q + 2) % 4], t[(q + 3) % 4])) > 0;
    if (forced) {
      ++account.forced;
      continue;
    }
    ++account.unforced;
    ++account.unforced_by_surface_nodes[on_surface[t[0]] + on_surface[t[1]] + on_surface[t[2]] + on_surface[t[3]]];
    if (account.max_unforced_tet < 0 || ratio > account.max_unforced_ratio) {
      account.max_unforced_ratio = ratio;
      account.max_unforced_tet = static_cast<int>(i);
    }
  }
  return account;
}

}  // namespace tissuemesh
