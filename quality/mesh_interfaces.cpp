#include "quality/mesh_interfaces.h"

#include "core/face_key.h"
#include "core/errors.h"
#include "core/junction_tracing.h"

#include <algorithm>
#include <cstdint>
#include <set>

namespace tissuemesh {
namespace {

struct FaceUse {
  std::array<int, 3> key;     ///< sorted node ids
  std::array<int, 3> outward; ///< winding with the normal out of the tet
  int region;                 ///< tissue id of the tet
};

}  // namespace

TriSurface interface_surface(const TetMesh& mesh, std::vector<int>* node_of_point) {
  std::vector<FaceUse> uses;
  uses.reserve(4 * mesh.tets.size());
  for (std::size_t t = 0; t < mesh.tets.size(); ++t) {
    const auto& k = mesh.tets[t];
    for (int i = 0; i < 4; ++i) {
      std::array<int, 3> f{k[(i + 1) % 4], k[(i + 2) % 4], k[(i + 3) % 4]};
      const Eigen::Vector3d &a = mesh.points[f[0]], &b = mesh.points[f[1]], &c = mesh.points[f[2]];
      if ((b - a).cross(c - a).dot(mesh.points[k[i]] - a) > 0.0) std::swap(f[1], f[2]);
      std::array<int, 3> key = f;
      std::sort(key.begin(), key.end());
      uses.push_back({key, f, mesh.tissue_ids[t]});
    }
  }
  std::sort(uses.begin(), uses.end(), [](const FaceUse& x, const FaceUse& y) {
    return x.key < y.key || (x.key == y.key && x.region < y.region);
  });

  TriSurface s;
  s.tissue_names = mesh.tissue_names;
  std::vector<std::array<int, 3>> tris;  // mesh node ids
  for (std::size_t i = 0; i < uses.size();) {
    std::size_t j = i;
    while (j < uses.size() && uses[j].key == uses[i].key) ++j;
    if (j - i > 2)
      throw InputError("mesh is not conforming: a face of nodes " + std::to_string(uses[i].key[0]) + ", " +
                       std::to_string(uses[i].key[1]) + ", " + std::to_string(uses[i].key[2]) + " is shared by " +
                       std::to_string(j - i) + " tets");
    if (j - i == 1) {  // boundary: outside (0) | tissue, normal from outside into the tissue
      const auto& f = uses[i].outward;
      tris.push_back({f[0], f[2], f[1]});
      s.labels.push_back({0, uses[i].region});
    } else if (uses[i].region != uses[i + 1].region) {  // sorted: uses[i] is the lower region p
      tris.push_back(uses[i].outward);
      s.labels.push_back({uses[i].region, uses[i + 1].region});
    }
    i = j;
  }

  // Points: the nodes the surface uses, in node order.
  std::vector<int> index(mesh.points.size(), -1);
  for (const auto& t : tris)
    for (int v : t) index[v] = 0;
  if (node_of_point) node_of_point->clear();
  for (std::size_t v = 0; v < mesh.points.size(); ++v)
    if (index[v] == 0) {
      index[v] = static_cast<int>(s.points.size());
      s.points.push_back(mesh.points[v]);
      if (node_of_point) node_of_point->push_back(static_cast<int>(v));
    }
  for (const auto& t : tris) s.triangles.push_back({index[t[0]], index[t[1]], index[t[2]]});

  // Junction edges: around them the incident triangles name >= 3 regions.
  std::vector<std::pair<std::uint64_t, int>> edge_regions;
  for (std::size_t t = 0; t < s.triangles.size(); ++t)
    for (int e = 0; e < 3; ++e)
      for (int region : s.labels[t])
        edge_regions.push_back({edge_key(s.triangles[t][e], s.triangles[t][(e + 1) % 3]), region});
  std::sort(edge_regions.begin(), edge_regions.end());
  edge_regions.erase(std::unique(edge_regions.begin(), edge_regions.end()), edge_regions.end());
  std::vector<std::vector<int>> adj(s.points.size());
  std::vector<std::set<int>> regions_at(s.points.size());
  for (std::size_t i = 0; i < edge_regions.size();) {
    std::size_t j = i;
    while (j < edge_regions.size() && edge_regions[j].first == edge_regions[i].first) ++j;
    const auto [a, b] = edge_of_key(edge_regions[i].first);
    for (std::size_t k = i; k < j; ++k) {
      regions_at[a].insert(edge_regions[k].second);
      regions_at[b].insert(edge_regions[k].second);
    }
    if (j - i >= 3) {
      adj[a].push_back(b);
      adj[b].push_back(a);
    }
    i = j;
  }
  std::vector<VertexKind> kind(s.points.size(), VertexKind::Surface);
  for (std::size_t v = 0; v < s.points.size(); ++v) {
    std::sort(adj[v].begin(), adj[v].end());
    if (adj[v].size() == 2)
      kind[v] = VertexKind::Curve;
    else if (!adj[v].empty() || regions_at[v].size() > 2)
      kind[v] = VertexKind::Corner;
  }
  s.junctions = trace_junctions(adj, kind);
  return s;
}

}  // namespace tissuemesh
