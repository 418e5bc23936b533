#include "volume/tet_volume_restoration.h"

#include "quality/mesh_interfaces.h"
#include "quality/mesh_quality.h"

#include <algorithm>
#include <vector>

namespace tissuemesh {

namespace {
// A move may not take a tet's smallest dihedral under this (or under its own, if it was smaller).
constexpr double kMinDihedralDeg = 10.0;
}  // namespace

TetVolumeRestoration restore_tet_volumes(TetMesh& mesh, const std::map<int, double>& reference_mm3,
                                         double max_total_move_mm) {
  TetVolumeRestoration result;
  std::vector<int> node_of_point;
  TriSurface surface = interface_surface(mesh, &node_of_point);
  std::vector<int> point_of_node(mesh.points.size(), -1);
  for (std::size_t i = 0; i < node_of_point.size(); ++i) point_of_node[node_of_point[i]] = static_cast<int>(i);
  // The tets around surface nodes: the only ones a move changes.
  std::vector<int> touched;
  std::vector<double> floor_deg;  // the smallest dihedral a move may leave each

  for (std::size_t t = 0; t < mesh.tets.size(); ++t) {
    const auto& k = mesh.tets[t];
    if (std::none_of(k.begin(), k.end(), [&](int n) { return point_of_node[n] >= 0; })) continue;
    touched.push_back(static_cast<int>(t));
    const double before =
        tet_volume_and_min_dihedral(mesh.points[k[0]], mesh.points[k[1]], mesh.points[k[2]], mesh.points[k[3]])
            .min_dihedral_deg;
    floor_deg.push_back(std::min(before, kMinDihedralDeg));
  }
  auto position = [&](const TriSurface& moved, int n) -> const Eigen::Vector3d& {
    return point_of_node[n] >= 0 ? moved.points[point_of_node[n]] : mesh.points[n];
  };
  // A round is acceptable when every tet stays positive and keeps its dihedral floor; the surface
  // nodes of one that does not are held. The surface itself may be non-manifold at a vertex (tets
  // of one tissue meeting at a point), which the tets allow: only they are checked.
  const RestorationCheck tets_stay = [&](const TriSurface& moved, std::vector<int>& bad_vertices) {
    for (std::size_t i = 0; i < touched.size(); ++i) {
      const auto& k = mesh.tets[touched[i]];
      const TetVolumeAndAngle shape = tet_volume_and_min_dihedral(position(moved, k[0]), position(moved, k[1]),
                                                         position(moved, k[2]), position(moved, k[3]));
      if (shape.volume_mm3 > 0.0 && shape.min_dihedral_deg >= floor_deg[i]) continue;
      for (int n : k)
        if (point_of_node[n] >= 0) bad_vertices.push_back(point_of_node[n]);
    }
    return bad_vertices.empty();
  };
  result.offsets = restore_volumes(surface, reference_mm3, 1e-4, 8, tets_stay, max_total_move_mm);
  for (std::size_t i = 0; i < node_of_point.size(); ++i) {
    Eigen::Vector3d& x = mesh.points[node_of_point[i]];
    if (surface.points[i] == x) continue;
    result.max_offset_mm = std::max(result.max_offset_mm, (surface.points[i] - x).norm());
    x = surface.points[i];
    ++result.nodes_moved;
  }
  return result;
}

}  // namespace tissuemesh
