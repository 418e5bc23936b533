#include "volume/boundary_slivers.h"

#include "core/face_key.h"
#include "quality/mesh_quality.h"
#include "quality/tet_faces.h"

#include <array>
#include <cstdint>
#include <unordered_map>

namespace tissuemesh {

namespace {

double min_dihedral(const TetMesh& m, const std::array<int, 4>& t) {
  return tet_volume_and_min_dihedral(m.points[t[0]], m.points[t[1]], m.points[t[2]], m.points[t[3]]).min_dihedral_deg;
}

}  // namespace

BoundarySliverRemoval remove_boundary_slivers(TetMesh& mesh, double min_dihedral_deg) {
  BoundarySliverRemoval r;
  r.removed_per_tissue.assign(mesh.num_tissues(), 0);
  if (mesh.points.size() >= kMaxFaceKeyNodes) return r;  // beyond the face-key range: leave as is
  const std::size_t num_tets = mesh.tets.size();
  const TetFaces face = number_tet_faces(mesh.tets);
  std::vector<int> uses(face.count, 0);  // number of live tets on each face
  for (int f : face.id) ++uses[static_cast<std::size_t>(f)];
  // Boundary faces per edge: removing a cap must not give an edge more than two of them.
  std::unordered_map<std::uint64_t, int> boundary_edge_faces;
  auto count_face_edges = [&](const std::array<int, 4>& t, int skip, int delta) {
    const int v[3] = {t[(skip + 1) % 4], t[(skip + 2) % 4], t[(skip + 3) % 4]};
    for (int k = 0; k < 3; ++k) boundary_edge_faces[edge_key(v[k], v[(k + 1) % 3])] += delta;
  };
  for (std::size_t i = 0; i < num_tets; ++i)
    for (int q = 0; q < 4; ++q)
      if (uses[face.of(i, q)] == 1) count_face_edges(mesh.tets[i], q, +1);
  std::vector<char> alive(mesh.tets.size(), 1);
  bool changed = true;
  while (changed) {
    changed = false;
    for (std::size_t i = 0; i < num_tets; ++i) {
      if (!alive[i]) continue;
      const auto& t = mesh.tets[i];
      int outer = 0;
      std::array<bool, 4> is_outer{};
      for (int q = 0; q < 4; ++q) outer += (is_outer[q] = uses[face.of(i, q)] == 1);
      if (outer < 2 || min_dihedral(mesh, t) >= min_dihedral_deg) continue;
      if (outer == 2) {
        // The two inner faces share the edge opposite the outer faces' common edge; it must not
        // be on the boundary already, or it would end up with four boundary faces.
        int shared[2], n = 0;
        for (int q = 0; q < 4; ++q)
          if (is_outer[q]) shared[n++] = t[q];  // face q is opposite vertex q
        if (boundary_edge_faces[edge_key(shared[0], shared[1])] > 0) continue;
      }
      alive[i] = 0;
      for (int q = 0; q < 4; ++q) {
        const bool was_outer = uses[face.of(i, q)] == 1;
        --uses[face.of(i, q)];
        // An outer face leaves the boundary; an inner face joins it (its other tet remains).
        count_face_edges(t, q, was_outer ? -1 : +1);
      }
      ++r.tets_removed;
      ++r.removed_per_tissue[mesh.tissue_ids[i] - 1];
      r.volume_removed_mm3 += signed_tet_volume(mesh.points[t[0]], mesh.points[t[1]], mesh.points[t[2]],
                                                mesh.points[t[3]]);
      changed = true;
    }
  }
  if (r.tets_removed == 0) return r;
  keep_tets(mesh, alive);
  return r;
}

}  // namespace tissuemesh
