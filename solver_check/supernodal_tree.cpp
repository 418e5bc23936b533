#include "solver_check/supernodal_tree.h"

#include <algorithm>
#include <numeric>
#include <stdexcept>
#include <string>

namespace tissuemesh {
namespace {

/// Opening stops when the larger bin holds at most this much more than half the bins' work
/// (closer balance than the two threads' noise buys nothing), or after this many steps.
constexpr double kBalance = 1.05;
constexpr int kMaxOpened = 256;

}  // namespace

std::vector<int> supernode_parents(const SupernodalFactorView& f) {
  auto refuse = [](const std::string& what) { throw std::invalid_argument("supernodal factor: " + what); };
  const int ns = f.nsuper;
  if (f.n <= 0 || ns <= 0 || f.super[0] != 0 || f.super[ns] != f.n || f.pi[0] != 0 || f.px[0] != 0)
    refuse("the supernodes do not cover the columns 0.." + std::to_string(f.n - 1));
  std::vector<char> seen(f.n, 0);
  for (int k = 0; k < f.n; ++k) {
    const int p = f.perm ? f.perm[k] : k;
    if (p < 0 || p >= f.n || seen[p]++) refuse("the permutation is not one of 0.." + std::to_string(f.n - 1));
  }
  std::vector<int> col_super(f.n, -1);  // the supernode of each column
  for (int s = 0; s < ns; ++s) {
    const int nscol = f.super[s + 1] - f.super[s], nsrow = f.pi[s + 1] - f.pi[s];
    if (nscol <= 0 || nsrow < nscol || f.px[s + 1] - f.px[s] < static_cast<long long>(nsrow) * nscol)
      refuse("supernode " + std::to_string(s) + " has an inconsistent block");
    for (int i = 0; i < nsrow; ++i) {
      const int r = f.rows[f.pi[s] + i];
      if (i < nscol ? r != f.super[s] + i : r < f.super[s + 1] || r >= f.n)
        refuse("supernode " + std::to_string(s) + " has row " + std::to_string(r) + " at position " + std::to_string(i));
    }
    for (int j = 0; j < nscol; ++j) col_super[f.super[s] + j] = s;
  }
  std::vector<int> parent(ns, -1);
  for (int s = 0; s < ns; ++s) {
    const int nscol = f.super[s + 1] - f.super[s], nsrow = f.pi[s + 1] - f.pi[s];
    if (nsrow > nscol) parent[s] = col_super[f.rows[f.pi[s] + nscol]];
    if (parent[s] >= 0 && parent[s] <= s) refuse("the elimination tree is not ordered");
  }
  return parent;
}

TreeSplit split_tree(const std::vector<int>& parent, const std::vector<double>& own_work) {
  const int ns = static_cast<int>(parent.size());
  std::vector<int> first(ns), count(ns, 1);
  std::vector<double> work = own_work;  // becomes each subtree's
  std::vector<std::vector<int>> children(ns);
  std::iota(first.begin(), first.end(), 0);
  double total = 0.0;
  for (int s = 0; s < ns; ++s) {
    total += own_work[s];
    if (parent[s] >= 0) {
      children[parent[s]].push_back(s);
      work[parent[s]] += work[s];  // work[s] is complete: all of s's descendants come before s
      first[parent[s]] = std::min(first[parent[s]], first[s]);
      count[parent[s]] += count[s];
    }
  }
  // Subtrees are contiguous ranges only in a postordered tree; otherwise no split.
  bool postordered = true;
  for (int s = 0; s < ns; ++s) postordered = postordered && count[s] == s - first[s] + 1;

  // A nested-dissection tree often starts with a chain of separator supernodes that must all be
  // opened before it branches, hence the search over opening steps.
  std::vector<int> open;
  for (int s = 0; s < ns; ++s)
    if (parent[s] < 0) open.push_back(s);
  double top_work = 0.0, best_time = total;
  auto by_work = [&](int a, int b) { return work[a] > work[b] || (work[a] == work[b] && a < b); };
  std::array<std::vector<int>, 2> assigned;
  for (int opened = 0; postordered && !open.empty() && opened <= kMaxOpened; ++opened) {
    std::sort(open.begin(), open.end(), by_work);
    std::array<double, 2> load{0.0, 0.0};
    std::array<std::vector<int>, 2> bins;
    for (int s : open) {
      const int b = load[1] < load[0] ? 1 : 0;
      load[b] += work[s];
      bins[b].push_back(s);
    }
    const double time = top_work + std::max(load[0], load[1]);
    if (!bins[1].empty() && time < best_time) {
      best_time = time;
      assigned = bins;
    }
    const int largest = open.front();
    if (children[largest].empty() || std::max(load[0], load[1]) <= kBalance * 0.5 * (load[0] + load[1])) break;
    top_work += own_work[largest];
    if (top_work >= best_time) break;  // no later step can beat the best
    open.erase(open.begin());
    open.insert(open.end(), children[largest].begin(), children[largest].end());
  }
  TreeSplit split;
  std::vector<char> in_bin(ns, 0);
  for (int b = 0; b < 2; ++b) {
    for (int root : assigned[b]) {
      split.bins[b].push_back({first[root], root});
      std::fill(in_bin.begin() + first[root], in_bin.begin() + root + 1, 1);
    }
    std::sort(split.bins[b].begin(), split.bins[b].end(),
              [](const SubtreeRange& a, const SubtreeRange& c) { return a.first < c.first; });
  }
  for (int s = 0; s < ns; ++s)
    if (!in_bin[s]) split.top.push_back(s);
  return split;
}

}  // namespace tissuemesh
