#include "mesher/boundary_slivers.h"

#include "mesher/mesh_quality.h"

#include <algorithm>
#include <array>
#include <map>

namespace tissuemesh {

namespace {

using Face = std::array<int, 3>;

Face face_of(const std::array<int, 4>& t, int skip) {
  Face f{};
  int n = 0;
  for (int q = 0; q < 4; ++q)
    if (q != skip) f[n++] = t[q];
  std::sort(f.begin(), f.end());
  return f;
}

double min_dihedral(const TetMesh& m, const std::array<int, 4>& t) {
  const TetShape s = tet_shape(m.points[t[0]], m.points[t[1]], m.points[t[2]], m.points[t[3]]);
  return *std::min_element(s.dihedral_deg.begin(), s.dihedral_deg.end());
}

}  // namespace

BoundarySliverRemoval remove_boundary_slivers(TetMesh& mesh, double min_dihedral_deg) {
  BoundarySliverRemoval r;
  r.removed_per_tissue.assign(mesh.num_tissues(), 0);
  std::map<Face, int> uses;  // number of live tets on each face
  for (const auto& t : mesh.tets)
    for (int q = 0; q < 4; ++q) ++uses[face_of(t, q)];
  std::vector<char> alive(mesh.tets.size(), 1);
  bool changed = true;
  while (changed) {
    changed = false;
    for (std::size_t i = 0; i < mesh.tets.size(); ++i) {
      if (!alive[i]) continue;
      const auto& t = mesh.tets[i];
      int outer = 0;
      for (int q = 0; q < 4; ++q) outer += uses[face_of(t, q)] == 1;
      if (outer < 2 || min_dihedral(mesh, t) >= min_dihedral_deg) continue;
      alive[i] = 0;
      for (int q = 0; q < 4; ++q) --uses[face_of(t, q)];
      ++r.tets_removed;
      ++r.removed_per_tissue[mesh.tissue_ids[i] - 1];
      r.volume_removed_mm3 += signed_tet_volume(mesh.points[t[0]], mesh.points[t[1]], mesh.points[t[2]],
                                                mesh.points[t[3]]);
      changed = true;
    }
  }
  if (r.tets_removed == 0) return r;
  // Compact tets, then nodes (keeping their order so the result stays deterministic).
  std::vector<std::array<int, 4>> tets;
  std::vector<int> ids;
  for (std::size_t i = 0; i < mesh.tets.size(); ++i)
    if (alive[i]) {
      tets.push_back(mesh.tets[i]);
      ids.push_back(mesh.tissue_ids[i]);
    }
  std::vector<int> new_index(mesh.points.size(), -1);
  for (const auto& t : tets)
    for (int v : t) new_index[v] = 0;
  std::vector<Eigen::Vector3d> points;
  for (std::size_t v = 0; v < mesh.points.size(); ++v)
    if (new_index[v] == 0) {
      new_index[v] = static_cast<int>(points.size());
      points.push_back(mesh.points[v]);
    }
  for (auto& t : tets)
    for (int& v : t) v = new_index[v];
  mesh.points.swap(points);
  mesh.tets.swap(tets);
  mesh.tissue_ids.swap(ids);
  return r;
}

}  // namespace tissuemesh
