// Why from the bounding triangles and not by a point-in-tissue test: the cells in question are
// slivers between folded triangles, thinner than any robust inside test, while the triangles'
// labels say exactly which side is which tissue.
#include "volume/unseeded_cells.h"

#include "core/face_key.h"
#include "core/number_format.h"
#include "core/union_find.h"

#include <map>
#include <unordered_map>

namespace tissuemesh {

UnseededCells label_unseeded_cells(const std::vector<Eigen::Vector3d>& points,
                                   const std::vector<std::array<int, 4>>& tets, const TriSurface& surface,
                                   std::vector<int>& ids) {
  UnseededCells result;
  std::vector<int> unseeded;
  for (std::size_t t = 0; t < tets.size(); ++t)
    if (ids[t] == 0) unseeded.push_back(static_cast<int>(t));
  if (unseeded.empty()) return result;

  std::unordered_map<std::uint64_t, int> triangle_of;  // surface triangle by its nodes
  for (std::size_t i = 0; i < surface.triangles.size(); ++i) {
    const auto& w = surface.triangles[i];
    triangle_of.emplace(face_key(w[0], w[1], w[2]), static_cast<int>(i));
  }
  // Faces of the unseeded tets that are not surface triangles join them into groups.
  std::unordered_map<std::uint64_t, std::vector<int>> inner_faces;
  for (int t : unseeded)
    for (int q = 0; q < 4; ++q) {
      const auto& k = tets[t];
      const std::uint64_t key = face_key(k[(q + 1) % 4], k[(q + 2) % 4], k[(q + 3) % 4]);
      if (!triangle_of.count(key)) inner_faces[key].push_back(t);
    }
  std::vector<int> parent = singleton_sets(tets.size());
  auto root = [&](int t) { return find_root(parent, t); };
  for (const auto& [key, members] : inner_faces)
    for (std::size_t m = 1; m < members.size(); ++m) {
      const int a = root(members[0]), b = root(members[m]);
      if (a != b) parent[std::max(a, b)] = std::min(a, b);
    }
  // Per group: the area of bounding surface triangles that put it on each region's side.
  std::map<int, std::map<int, double>> side_area;
  for (int t : unseeded) {
    const auto& k = tets[t];
    for (int q = 0; q < 4; ++q) {
      const auto found = triangle_of.find(face_key(k[(q + 1) % 4], k[(q + 2) % 4], k[(q + 3) % 4]));
      if (found == triangle_of.end()) continue;
      const auto& w = surface.triangles[found->second];
      const Eigen::Vector3d n = (points[w[1]] - points[w[0]]).cross(points[w[2]] - points[w[0]]);
      const bool on_q_side = n.dot(points[k[q]] - points[w[0]]) > 0.0;  // the normal points from p into q
      const auto& labels = surface.labels[found->second];
      side_area[root(t)][on_q_side ? labels[1] : labels[0]] += 0.5 * n.norm();
    }
  }
  std::map<int, int> tissue_of_group;
  for (const auto& [group, areas] : side_area) {
    int best = 0;
    double most = -1.0;
    for (const auto& [region, area] : areas)
      if (area > most) best = region, most = area;
    tissue_of_group[group] = best;
  }
  std::map<int, char> counted;
  for (int t : unseeded) {
    const auto it = tissue_of_group.find(root(t));
    if (it == tissue_of_group.end() || it->second == 0) continue;
    ids[t] = it->second;
    ++result.tets;
    const auto& k = tets[t];
    result.volume_mm3 += signed_tet_volume(points[k[0]], points[k[1]], points[k[2]], points[k[3]]);
    counted[root(t)] = 1;
  }
  result.groups = counted.size();
  return result;
}

std::string unseeded_warning(const UnseededCells& u) {
  if (u.tets == 0) return "";
  return std::to_string(u.tets) + " tets in " + std::to_string(u.groups) +
         " cells that folds of the surface enclose (" + format_double("%.3g", u.volume_mm3) +
         " mm^3) were in no region of TetGen's and got the tissue around them";
}

}  // namespace tissuemesh
