#include "core/junction_tracing.h"

#include <algorithm>
#include <set>
#include <utility>

namespace tissuemesh {

std::vector<std::vector<int>> trace_junctions(const std::vector<std::vector<int>>& adj,
                                              const std::vector<VertexKind>& kind) {
  std::set<std::pair<int, int>> used;
  auto take = [&](int a, int b) { return used.insert({std::min(a, b), std::max(a, b)}).second; };
  std::vector<std::vector<int>> lines;
  auto follow = [&](int start, int next) {
    std::vector<int> line{start};
    int prev = start, cur = next;
    while (true) {
      line.push_back(cur);
      if (cur == start || kind[static_cast<std::size_t>(cur)] != VertexKind::Curve) break;
      const auto& n = adj[static_cast<std::size_t>(cur)];
      const int after = n[0] == prev ? n[1] : n[0];
      if (!take(cur, after)) break;
      prev = cur;
      cur = after;
    }
    lines.push_back(std::move(line));
  };
  for (std::size_t v = 0; v < adj.size(); ++v)
    if (kind[v] == VertexKind::Corner)
      for (int w : adj[v])
        if (take(static_cast<int>(v), w)) follow(static_cast<int>(v), w);
  for (std::size_t v = 0; v < adj.size(); ++v)
    if (kind[v] == VertexKind::Curve)
      for (int w : adj[v])
        if (take(static_cast<int>(v), w)) follow(static_cast<int>(v), w);
  return lines;
}

}  // namespace tissuemesh
