// Dropping RemeshComplex's dead vertices and triangles (surface/remesh_complex.h): in place
// (compact: the coarsening leaves most of the extracted surface dead in the arrays every sweep
// walks) and into the resulting TriSurface (result, which also chains the junction polylines).
#include "surface/remesh_complex.h"

#include "core/errors.h"
#include "core/face_key.h"

#include <algorithm>
#include <unordered_map>

namespace tissuemesh {

void RemeshComplex::compact() {
  // New indices in the old order: every comparison of indices (sweep order, tie-breaks, sorted
  // rings) keeps its outcome, so the remesher's results do not change.
  std::vector<int> vertex_index(x_.size(), -1), triangle_index(tri_.size(), -1);
  int nv = 0, nt = 0;
  for (std::size_t v = 0; v < x_.size(); ++v)
    if (vertex_alive_[v]) vertex_index[v] = nv++;
  for (std::size_t t = 0; t < tri_.size(); ++t)
    if (tri_alive_[t]) triangle_index[t] = nt++;
  if (nv == static_cast<int>(x_.size()) && nt == static_cast<int>(tri_.size())) return;
  const bool rings_tracked = ring_changed_.size() == x_.size();  // collapse_until_stable reads them next
  for (std::size_t v = 0; v < x_.size(); ++v) {
    const int n = vertex_index[v];
    if (n < 0) continue;
    if (n != static_cast<int>(v)) {  // (a vector moved onto itself would come out empty)
      x_[n] = x_[v];
      kind_[n] = kind_[v];
      owner_[n] = owner_[v];
      represents_[n] = std::move(represents_[v]);
      vt_[n] = std::move(vt_[v]);
      if (rings_tracked) ring_changed_[n] = ring_changed_[v];
    }
    for (int& t : vt_[n]) t = triangle_index[t];
  }
  x_.resize(nv);
  kind_.resize(nv);
  owner_.resize(nv);
  represents_.resize(nv);
  vt_.resize(nv);
  if (rings_tracked) ring_changed_.resize(nv);
  vertex_alive_.assign(nv, 1);
  for (std::size_t t = 0; t < tri_.size(); ++t) {
    const int n = triangle_index[t];
    if (n < 0) continue;
    for (int i = 0; i < 3; ++i) tri_[n][i] = vertex_index[tri_[t][i]];
    patch_[n] = patch_[t];
  }
  tri_.resize(nt);
  patch_.resize(nt);
  tri_alive_.assign(nt, 1);
  std::unordered_map<std::uint64_t, int> curve_edge;
  for (const auto& [key, curve] : curve_edge_) {
    const auto [a, b] = edge_of_key(key);
    curve_edge[edge_key(vertex_index[a], vertex_index[b])] = curve;
  }
  curve_edge_ = std::move(curve_edge);
  for (Scratch& sc : scratch_) {
    sc.seen.assign(nt, 0);
    sc.stamp = 0;
  }
  grid_cell_ = 0.0;
  rebuild_grid();  // on the new triangle ids
}

TriSurface RemeshComplex::result(const TriSurface& in) const {
  TriSurface out;
  out.tissue_names = in.tissue_names;
  std::vector<int> index(x_.size(), -1);
  for (std::size_t v = 0; v < x_.size(); ++v)
    if (vertex_alive_[v]) {
      index[v] = static_cast<int>(out.points.size());
      out.points.push_back(x_[v]);
    }
  for (std::size_t t = 0; t < tri_.size(); ++t) {
    if (!tri_alive_[t]) continue;
    out.triangles.push_back({index[tri_[t][0]], index[tri_[t][1]], index[tri_[t][2]]});
    out.labels.push_back(proj_.patches().pair_of_patch[patch_[t]]);
  }
  // Junction polylines: chain each curve's edges, from an end (open) or its lowest vertex (closed).
  std::vector<std::vector<std::array<int, 2>>> by_curve(curve_edges_.size());
  for (const auto& kv : curve_edge_)
    by_curve[kv.second].push_back(edge_of_key(kv.first));
  for (std::size_t c = 0; c < by_curve.size(); ++c) {
    auto& es = by_curve[c];
    if (es.empty()) throw MeshingError("surface remeshing lost junction polyline " + std::to_string(c));
    std::sort(es.begin(), es.end());
    std::unordered_map<int, std::vector<int>> adj;
    for (const auto& e : es) {
      adj[e[0]].push_back(e[1]);
      adj[e[1]].push_back(e[0]);
    }
    int start = -1;  // open: the lowest-indexed end; closed: the lowest vertex
    for (const auto& kv : adj)
      if (kv.second.size() == 1 && (start < 0 || kv.first < start)) start = kv.first;
    if (start < 0) start = es.front()[0];
    std::vector<int> line{start};
    int prev = -1, cur = start;
    for (std::size_t k = 0; k < es.size(); ++k) {
      int n = -1;
      for (int w : adj[cur])
        if (w != prev && (n < 0 || w < n)) n = w;
      if (n < 0) break;
      prev = cur;
      cur = n;
      line.push_back(cur);
    }
    if (line.size() != es.size() + 1)
      throw MeshingError("surface remeshing broke junction polyline " + std::to_string(c));
    for (int& v : line) {
      if (index[v] < 0) throw MeshingError("surface remeshing left a removed vertex on junction polyline " + std::to_string(c));
      v = index[v];
    }
    out.junctions.push_back(std::move(line));
  }
  return out;
}

}  // namespace tissuemesh
