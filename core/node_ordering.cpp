// Why: FEBio built without MKL solves with a skyline (profile) solver whose memory and time grow
// with the matrix profile, so the model's default numbering keeps the profile small
// (docs/formats.md, "FEBio"). RCM is the classic profile reducer and is cheap; everything here is
// deterministic so that the same mesh always gives the same model files.
#include "core/node_ordering.h"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace tissuemesh {

namespace {

void check_arguments(int num_nodes, const std::vector<std::array<int, 10>>& elements, int nodes_per_element) {
  if (num_nodes < 0) throw std::invalid_argument("node ordering: negative node count");
  if (nodes_per_element < 1 || nodes_per_element > 10)
    throw std::invalid_argument("node ordering: nodes_per_element " + std::to_string(nodes_per_element) +
                                " is outside 1..10");
  for (std::size_t e = 0; e < elements.size(); ++e)
    for (int k = 0; k < nodes_per_element; ++k)
      if (elements[e][k] >= num_nodes)
        throw std::invalid_argument("node ordering: element " + std::to_string(e) + " uses node " +
                                    std::to_string(elements[e][k]) + " of " + std::to_string(num_nodes));
}

// Node adjacency in compressed rows (no self loops, no duplicates), each row sorted by
// (degree, index): the order Cuthill-McKee visits neighbours in.
struct Graph {
  std::vector<int> start, adj, degree;
  int neighbours_begin(int v) const { return start[v]; }
  int neighbours_end(int v) const { return start[v + 1]; }
};

Graph node_graph(int n, const std::vector<std::array<int, 10>>& elements, int npe) {
  // Gathered in compressed rows by counting (every pair of an element's nodes, repeats included),
  // then sorted and made unique row by row.
  const auto valid = [](const std::array<int, 10>& el, int a, int b) { return el[a] >= 0 && el[b] >= 0 && el[a] != el[b]; };
  std::vector<int> at(static_cast<std::size_t>(n) + 1, 0);
  for (const auto& el : elements)
    for (int a = 0; a < npe; ++a)
      for (int b = 0; b < npe; ++b)
        if (a != b && valid(el, a, b)) ++at[el[a] + 1];
  for (int v = 0; v < n; ++v) at[v + 1] += at[v];
  std::vector<int> pairs(static_cast<std::size_t>(at[n]));
  std::vector<int> fill(at.begin(), at.end() - 1);
  for (const auto& el : elements)
    for (int a = 0; a < npe; ++a)
      for (int b = 0; b < npe; ++b)
        if (a != b && valid(el, a, b)) pairs[fill[el[a]]++] = el[b];
  Graph g;
  g.degree.resize(static_cast<std::size_t>(n));
  g.start.assign(static_cast<std::size_t>(n) + 1, 0);
  for (int v = 0; v < n; ++v) {
    const auto begin = pairs.begin() + at[v], end = pairs.begin() + at[v + 1];
    std::sort(begin, end);
    g.degree[v] = static_cast<int>(std::unique(begin, end) - begin);
    g.start[v + 1] = g.start[v] + g.degree[v];
  }
  g.adj.resize(static_cast<std::size_t>(g.start[n]));
  for (int v = 0; v < n; ++v) {
    const auto row = g.adj.begin() + g.start[v];
    std::copy(pairs.begin() + at[v], pairs.begin() + at[v] + g.degree[v], row);
    std::sort(row, row + g.degree[v],
              [&](int x, int y) { return g.degree[x] != g.degree[y] ? g.degree[x] < g.degree[y] : x < y; });
  }
  return g;
}

// Breadth-first level structure rooted at `root` (it covers root's component). Returns the nodes
// level by level; `levels` receives the number of levels and `last` the start of the last level in
// the returned list. Marks visited nodes with `stamp` in `seen` (a fresh stamp per call).
std::vector<int> level_structure(const Graph& g, int root, std::vector<int>& seen, int stamp, int& levels,
                                 std::size_t& last) {
  std::vector<int> order{root};
  seen[root] = stamp;
  std::size_t begin = 0;
  levels = 0;
  while (begin < order.size()) {
    const std::size_t end = order.size();
    last = begin;
    ++levels;
    for (std::size_t i = begin; i < end; ++i)
      for (int p = g.neighbours_begin(order[i]); p < g.neighbours_end(order[i]); ++p)
        if (seen[g.adj[p]] != stamp) {
          seen[g.adj[p]] = stamp;
          order.push_back(g.adj[p]);
        }
    begin = end;
  }
  return order;
}

// Lowest-index node of minimum degree among nodes[from..].
int min_degree_node(const Graph& g, const std::vector<int>& nodes, std::size_t from) {
  int best = nodes[from];
  for (std::size_t i = from + 1; i < nodes.size(); ++i) {
    const int v = nodes[i];
    if (g.degree[v] < g.degree[best] || (g.degree[v] == g.degree[best] && v < best)) best = v;
  }
  return best;
}

}  // namespace

std::vector<int> reverse_cuthill_mckee(int num_nodes, const std::vector<std::array<int, 10>>& elements,
                                       int nodes_per_element) {
  check_arguments(num_nodes, elements, nodes_per_element);
  const Graph g = node_graph(num_nodes, elements, nodes_per_element);
  std::vector<int> new_index(static_cast<std::size_t>(num_nodes), -1);
  std::vector<int> seen(static_cast<std::size_t>(num_nodes), -1);
  int stamp = 0, next = 0;
  for (int first = 0; first < num_nodes; ++first) {
    if (new_index[first] >= 0) continue;
    // The component of `first` (its lowest-index node: lower ones are all numbered already).
    int levels = 0;
    std::size_t last = 0;
    const std::vector<int> component = level_structure(g, first, seen, stamp++, levels, last);
    // Pseudo-peripheral start (George & Liu).
    int root = min_degree_node(g, component, 0);
    std::vector<int> rooted = level_structure(g, root, seen, stamp++, levels, last);
    for (;;) {
      const int candidate = min_degree_node(g, rooted, last);
      int candidate_levels = 0;
      std::size_t candidate_last = 0;
      std::vector<int> from_candidate = level_structure(g, candidate, seen, stamp++, candidate_levels, candidate_last);
      if (candidate_levels <= levels) break;
      root = candidate;
      rooted = std::move(from_candidate);
      levels = candidate_levels;
      last = candidate_last;
    }
    // Cuthill-McKee from the root, neighbours by (degree, index) as stored; then reversed.
    std::vector<int> cm{root};
    cm.reserve(component.size());
    const int tag = stamp++;
    seen[root] = tag;
    for (std::size_t i = 0; i < cm.size(); ++i)
      for (int p = g.neighbours_begin(cm[i]); p < g.neighbours_end(cm[i]); ++p)
        if (seen[g.adj[p]] != tag) {
          seen[g.adj[p]] = tag;
          cm.push_back(g.adj[p]);
        }
    for (auto it = cm.rbegin(); it != cm.rend(); ++it) new_index[*it] = next++;
  }
  return new_index;
}

long long matrix_profile(int num_nodes, const std::vector<std::array<int, 10>>& elements, int nodes_per_element) {
  check_arguments(num_nodes, elements, nodes_per_element);
  // Lowest column of row i = the lowest node of any element holding i (or i itself).
  std::vector<int> low(static_cast<std::size_t>(num_nodes));
  for (int i = 0; i < num_nodes; ++i) low[i] = i;
  for (const auto& el : elements) {
    int m = num_nodes;
    for (int k = 0; k < nodes_per_element; ++k)
      if (el[k] >= 0) m = std::min(m, el[k]);
    for (int k = 0; k < nodes_per_element; ++k)
      if (el[k] >= 0) low[el[k]] = std::min(low[el[k]], m);
  }
  long long sum = 0;
  for (int i = 0; i < num_nodes; ++i) sum += i - low[i];
  return sum;
}

}  // namespace tissuemesh
