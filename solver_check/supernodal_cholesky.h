// SupernodalCholesky: the numeric Cholesky factorisation of the built-in solver's tangent, into
// the supernodal factor that CHOLMOD's symbolic analysis laid out (solver_check/supernodal_tree.h),
// with the two bins of the elimination tree factorised on two threads at the same time and the
// top's wide supernodes by panels on both (right-looking supernodal Cholesky; the .cpp says why).
//
// Determinism: every entry receives the same operations in the same order whatever the thread
// count, so the factor depends on K and the shift only.
//
// Memory: the factor's own values (written in place) plus, when the tree splits, a buffer of the
// top supernodes' blocks (typically a fifth of the factor), the largest update per thread, and
// the map from K's entries to the factor's (one int per entry).
#pragma once

#include "solver_check/supernodal_tree.h"

#include <Eigen/SparseCore>

#include <cstdint>
#include <vector>

namespace tissuemesh {

class SupernodalCholesky {
 public:
  /// Plans the factorisation of matrices with K's pattern (lower triangle, compressed, original
  /// numbering: row k of L is unknown perm[k]) into the factor `factor` (its arrays must stay as
  /// they are while this object is used; `values` is overwritten by factorise()). Throws
  /// std::invalid_argument, before changing anything, for an inconsistent view (supernode_parents),
  /// a block whose rows below its own columns do not increase or are not all rows of the ancestor
  /// they update, a K that is not square of the factor's size or not compressed, or an entry of K
  /// outside the factor's pattern.
  void plan(const SupernodalFactorView& factor, const Eigen::SparseMatrix<double>& K);
  bool empty() const { return n_ == 0; }

  /// Overwrites the factor's values with the Cholesky factor of P (K + shift I) P^T, on `threads`
  /// threads (1 or 2 are used; the same bits for any count). Returns false when that matrix is not
  /// positive definite (a pivot not positive and finite); the values are then meaningless. Throws
  /// std::invalid_argument when nothing was planned or K's pattern is not the planned one. BLAS
  /// must run on one thread per call when `threads` > 1 (see the .cpp).
  bool factorise(const Eigen::SparseMatrix<double>& K, double shift, int threads);

  /// Share of the estimated flops in the top part (after both bins; 1 when the tree does not split).
  double top_share() const { return top_share_; }
  /// Whether the top has a supernode wide enough to be factorised by panels on two threads.
  bool panelled() const { return panelled_; }

 private:
  /// Supernode d's update of supernode `target`: its rows at positions first .. last - 1 are the
  /// target's columns.
  struct Send {
    int target, first, last;
  };
  /// Factorises supernode s (its block complete) and sends its updates; `bin` is s's bin, or -1
  /// for the top (updates of top supernodes from a bin go to that bin's buffer). False when s's
  /// diagonal block is not positive definite.
  /// A top supernode is factorised on `threads` threads when it is wide (the .cpp's
  /// kPanelledColumns), else on the caller's.
  bool eliminate(int s, int bin, std::vector<double>& product, std::vector<int>& position, int threads = 1);
  /// dpotrf and dtrsm of supernode s's block by panels, on up to two threads (the same bits for
  /// any count). False when the diagonal block is not positive definite.
  bool factorise_panelled(int s, int threads);

  int n_ = 0, nsuper_ = 0;
  const int* super_ = nullptr;
  const int* pi_ = nullptr;
  const int* px_ = nullptr;
  const int* rows_ = nullptr;
  double* values_ = nullptr;
  std::vector<int> outer_, inner_;         ///< K's planned pattern
  std::vector<int> destination_;           ///< of each of K's entries in values_
  std::vector<int> diagonal_;              ///< of each diagonal entry in values_
  std::vector<int> send_start_;            ///< nsuper + 1 offsets into sends_
  std::vector<Send> sends_;
  std::vector<int> bin_;                   ///< of each supernode: 0, 1, or -1 for the top
  TreeSplit split_;
  std::vector<std::int64_t> top_offset_;   ///< of each top supernode's block in the buffers
  std::vector<double> buffer_;             ///< bin 1's updates of top blocks
  std::vector<double> product_[2];         ///< work space for an update, per thread
  std::vector<int> position_[2];           ///< row positions in the target, per thread
  double top_share_ = 1.0;
  bool panelled_ = false;
};

}  // namespace tissuemesh
