#include "volume/boundary_pinches.h"

#include "core/face_key.h"
#include "core/union_find.h"
#include "quality/tet_faces.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <unordered_map>

namespace tissuemesh {

namespace {

double tet_volume(const TetMesh& m, const std::array<int, 4>& t) {
  return std::abs(signed_tet_volume(m.points[t[0]], m.points[t[1]], m.points[t[2]], m.points[t[3]]));
}

/// The pinched edges of the outer boundary (more than two boundary faces), in key order.
std::vector<std::uint64_t> pinched_edges(const TetMesh& mesh) {
  const TetFaces face = number_tet_faces(mesh.tets);
  std::vector<int> uses(face.count, 0);
  for (int f : face.id) ++uses[static_cast<std::size_t>(f)];
  std::unordered_map<std::uint64_t, int> faces_on_edge;
  for (std::size_t i = 0; i < mesh.tets.size(); ++i)
    for (int q = 0; q < 4; ++q) {
      if (uses[face.of(i, q)] != 1) continue;
      const auto& t = mesh.tets[i];
      const int v[3] = {t[(q + 1) % 4], t[(q + 2) % 4], t[(q + 3) % 4]};
      for (int k = 0; k < 3; ++k) ++faces_on_edge[edge_key(v[k], v[(k + 1) % 3])];
    }
  std::vector<std::uint64_t> pinched;
  for (const auto& [key, n] : faces_on_edge)
    if (n > 2) pinched.push_back(key);
  std::sort(pinched.begin(), pinched.end());
  return pinched;
}

}  // namespace

BoundaryPinchRepair open_boundary_pinches(TetMesh& mesh, int max_passes) {
  BoundaryPinchRepair r;
  r.removed_per_tissue.assign(mesh.num_tissues(), 0);
  r.volume_per_tissue_mm3.assign(mesh.num_tissues(), 0.0);
  if (mesh.points.size() >= kMaxFaceKeyNodes) return r;
  std::vector<std::uint64_t> pinched = pinched_edges(mesh);
  r.edges_found = pinched.size();
  while (!pinched.empty() && r.passes < max_passes) {
    ++r.passes;
    // Tets around each pinched edge, through the tets of its smaller node.
    std::vector<std::vector<int>> tets_of_node(mesh.points.size());
    std::vector<char> on_pinch(mesh.points.size(), 0);
    for (std::uint64_t key : pinched) on_pinch[edge_of_key(key)[0]] = 1;
    for (std::size_t i = 0; i < mesh.tets.size(); ++i)
      for (int v : mesh.tets[i])
        if (on_pinch[v]) tets_of_node[v].push_back(static_cast<int>(i));

    std::vector<char> keep(mesh.tets.size(), 1);
    for (std::uint64_t key : pinched) {
      const auto [a, b] = edge_of_key(key);
      std::vector<int> around;  // live tets holding both a and b
      for (int t : tets_of_node[a]) {
        const auto& tet = mesh.tets[t];
        if (keep[t] && std::find(tet.begin(), tet.end(), b) != tet.end()) around.push_back(t);
      }
      // Fans: tets around the edge joined across the faces that hold the edge.
      const int n = static_cast<int>(around.size());
      std::vector<int> parent = singleton_sets(static_cast<std::size_t>(n));
      auto others = [&](int t) {
        std::array<int, 2> o{};
        int k = 0;
        for (int v : mesh.tets[t])
          if (v != a && v != b && k < 2) o[k++] = v;
        return o;
      };
      for (int x = 0; x < n; ++x)
        for (int y = x + 1; y < n; ++y) {
          const auto ox = others(around[x]), oy = others(around[y]);
          if (ox[0] == oy[0] || ox[0] == oy[1] || ox[1] == oy[0] || ox[1] == oy[1])
            parent[find_root(parent, x)] = find_root(parent, y);
        }
      std::map<int, double> fan_volume;  // root -> volume
      for (int x = 0; x < n; ++x) fan_volume[find_root(parent, x)] += tet_volume(mesh, mesh.tets[around[x]]);
      if (fan_volume.size() < 2) continue;  // an earlier removal in this pass opened it
      int kept = -1;
      double best = -1.0;
      for (int x = 0; x < n; ++x) {  // around[] is in tet order: the first of equal fans wins
        const int root = find_root(parent, x);
        if (fan_volume[root] > best) {
          best = fan_volume[root];
          kept = root;
        }
      }
      for (int x = 0; x < n; ++x) {
        if (find_root(parent, x) == kept) continue;
        const int t = around[x];
        keep[t] = 0;
        const double v = tet_volume(mesh, mesh.tets[t]);
        const int tissue = mesh.tissue_ids[t];
        ++r.tets_removed;
        r.volume_removed_mm3 += v;
        ++r.removed_per_tissue[tissue - 1];
        r.volume_per_tissue_mm3[tissue - 1] += v;
      }
    }
    keep_tets(mesh, keep);
    pinched = pinched_edges(mesh);
  }
  r.edges_left = pinched.size();
  return r;
}

}  // namespace tissuemesh
