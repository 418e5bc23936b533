// Disjoint sets over the ids 0..n-1 as a parent array (union-find): parent[i] == i for a root.
// Callers join sets by setting the parent of one root to another; which root a set ends with
// depends only on the order of those joins, never on the path compression below.
#pragma once

#include <cstddef>
#include <numeric>
#include <vector>

namespace tissuemesh {

/// n sets of one id each.
inline std::vector<int> singleton_sets(std::size_t n) {
  std::vector<int> parent(n);
  std::iota(parent.begin(), parent.end(), 0);
  return parent;
}

/// The root of i's set; halves the path on the way (every node points to its grandparent).
inline int find_root(std::vector<int>& parent, int i) {
  while (parent[i] != i) i = parent[i] = parent[parent[i]];
  return i;
}

}  // namespace tissuemesh
