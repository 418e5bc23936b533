#include "volume/surface_pieces.h"

#include "core/union_find.h"

#include "core/face_key.h"

#include <algorithm>
#include <map>
#include <numeric>
#include <unordered_map>
#include <unordered_set>

namespace tissuemesh {

namespace {

void unite(std::vector<int>& parent, int a, int b) {
  a = find_root(parent, a);
  b = find_root(parent, b);
  if (a != b) parent[std::max(a, b)] = std::min(a, b);
}

}  // namespace

SurfacePieces manifold_pieces(const TriSurface& s) {
  const int nt = static_cast<int>(s.triangles.size());
  std::unordered_set<std::uint64_t> junction_edges;
  for (const auto& line : s.junctions)
    for (std::size_t i = 0; i + 1 < line.size(); ++i) junction_edges.insert(edge_key(line[i], line[i + 1]));

  // Triangles of the same pair around each edge.
  std::unordered_map<std::uint64_t, std::vector<int>> around;
  around.reserve(3 * s.triangles.size());
  for (int t = 0; t < nt; ++t)
    for (int e = 0; e < 3; ++e) around[edge_key(s.triangles[t][e], s.triangles[t][(e + 1) % 3])].push_back(t);

  std::vector<int> parent = singleton_sets(s.triangles.size());
  // `inner` marks the edges inside a piece (joined), used again for the fans below: two triangles
  // of one piece sharing an inner edge are joined across it (an edge with triangles of several
  // pairs is a junction edge, so an inner edge joins triangles of one pair only).
  std::unordered_set<std::uint64_t> inner;
  for (const auto& [key, tris] : around) {
    if (junction_edges.count(key)) continue;
    std::map<std::array<int, 2>, std::vector<int>> by_pair;
    for (int t : tris) by_pair[s.labels[t]].push_back(t);
    for (const auto& [pair, same] : by_pair)
      if (same.size() == 2) {
        unite(parent, same[0], same[1]);
        inner.insert(key);
      }
  }

  SurfacePieces out;
  std::map<int, int> piece_of_root;  // root triangle -> piece index, in order of first triangle
  for (int t = 0; t < nt; ++t) {
    const int root = find_root(parent, t);
    auto [it, fresh] = piece_of_root.emplace(root, static_cast<int>(out.pieces.size()));
    if (fresh) {
      out.pieces.emplace_back();
      out.pieces.back().pair = s.labels[t];
    }
    out.pieces[it->second].source_triangles.push_back(t);
  }

  for (SurfacePiece& piece : out.pieces) {
    // Fans around each vertex: the piece's triangles at the vertex, joined across inner edges
    // through the vertex.
    std::map<int, std::vector<int>> at_vertex;  // surface vertex -> piece-local triangle indices
    for (std::size_t lt = 0; lt < piece.source_triangles.size(); ++lt)
      for (int v : s.triangles[piece.source_triangles[lt]]) at_vertex[v].push_back(static_cast<int>(lt));
    std::vector<std::array<int, 3>> local(piece.source_triangles.size(), {-1, -1, -1});
    for (const auto& [v, tris] : at_vertex) {
      std::vector<int> fan = singleton_sets(tris.size());
      for (std::size_t i = 0; i < tris.size(); ++i)
        for (std::size_t j = i + 1; j < tris.size(); ++j) {
          const auto& a = s.triangles[piece.source_triangles[tris[i]]];
          const auto& b = s.triangles[piece.source_triangles[tris[j]]];
          for (int w : a)
            if (w != v && std::find(b.begin(), b.end(), w) != b.end() && inner.count(edge_key(v, w)))
              unite(fan, static_cast<int>(i), static_cast<int>(j));
        }
      std::map<int, int> copy_of_fan;
      for (std::size_t i = 0; i < tris.size(); ++i) {
        auto [it, fresh] = copy_of_fan.emplace(find_root(fan, static_cast<int>(i)), static_cast<int>(piece.points.size()));
        if (fresh) piece.points.push_back(s.points[v]);
        const auto& tri = s.triangles[piece.source_triangles[tris[i]]];
        for (int c = 0; c < 3; ++c)
          if (tri[c] == v) local[tris[i]][c] = it->second;
      }
      out.duplicated_vertices += copy_of_fan.size() - 1;
    }
    piece.triangles = std::move(local);
  }
  return out;
}

}  // namespace tissuemesh
