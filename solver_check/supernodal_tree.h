// Supernodal factors: the layout shared by the built-in solver's own supernodal routines and their
// checks, and the split of the supernodes' elimination tree between two threads.
//
// Factor layout (CHOLMOD's supernodal LL', read through SupernodalFactorView): A = P^T L L^T P;
// supernode s holds columns super[s] .. super[s+1]-1 of L as a dense column-major block of
// nsrow = pi[s+1] - pi[s] rows (row indices rows[pi[s]] ..., the first nscol of them the
// supernode's own columns) at values[px[s]]; its diagonal block is lower triangular.
//
// Split: in an elimination tree numbered in postorder (CHOLMOD's default) every subtree is a
// contiguous range of supernodes, and disjoint subtrees can be worked on at the same time. The
// split puts subtrees into two bins of about equal work and leaves the supernodes above them (the
// top: a nested-dissection ordering's separators) to be done after both bins.
#pragma once

#include <array>
#include <vector>

namespace tissuemesh {

/// Arrays of a supernodal LL' factor of an n x n matrix (the layout of the header comment).
struct SupernodalFactorView {
  int n = 0;
  int nsuper = 0;
  const int* super = nullptr;        ///< nsuper + 1 first columns
  const int* pi = nullptr;           ///< nsuper + 1 offsets into rows
  const int* px = nullptr;           ///< nsuper + 1 offsets into values
  const int* rows = nullptr;         ///< row indices of the supernodes' blocks
  double* values = nullptr;          ///< the blocks, column-major
  const int* perm = nullptr;         ///< perm[k]: the original index of row k of L (nullptr: identity)
};

/// Checks the view's consistency and returns each supernode's parent in the elimination tree
/// (the supernode of its first row below its own columns; -1 for a root). Throws
/// std::invalid_argument, naming the problem, for supernodes not covering the columns in order, a
/// block not starting with its own columns or smaller than its rows x columns, a row out of
/// range, a parent not after its child, or a permutation that is not one.
std::vector<int> supernode_parents(const SupernodalFactorView& factor);

/// Supernodes first .. last: a subtree in postorder.
struct SubtreeRange {
  int first, last;
};

/// Two bins of subtrees (each sorted by first supernode) and the top: the supernodes in no bin,
/// increasing. Both bins empty when the tree does not split (one chain, or not in postorder).
struct TreeSplit {
  std::array<std::vector<SubtreeRange>, 2> bins;
  std::vector<int> top;
  bool split() const { return !bins[0].empty() && !bins[1].empty(); }
};

/// Splits the tree given by `parent` (parent[s] > s or -1) by the work of each supernode (its
/// own, not its subtree's): the largest subtree is opened (its root joins the top) step by step,
/// and after each step the open subtrees go largest-first into the lighter bin; the split kept is
/// the step with the least estimated time, top + larger bin. A tree not in postorder is not split.
TreeSplit split_tree(const std::vector<int>& parent, const std::vector<double>& work);

}  // namespace tissuemesh
