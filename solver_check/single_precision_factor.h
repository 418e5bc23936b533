// SinglePrecisionFactor: a supernodal Cholesky factor converted to single precision in place, and
// its two triangular solves, split over two threads: the preconditioner of the built-in solver's
// conjugate gradients (solver_check/linear_solver.h).
//
// Memory: the factor's values are converted to single precision in place (the first half of
// their own array) and its index arrays are borrowed, so the preconditioner costs no memory beyond
// the factor's; the factor's double values are gone until it is factorised again.
//
// Factor layout: solver_check/supernodal_tree.h.
//
// Threads: the tree is split once per factor (assign) into two bins of subtrees of about equal
// size and a top part (the separators above them) solved by one thread. Each bin accumulates its
// updates of top rows in its own buffer; they are added in bin order. So the result depends on
// the factor and the right-hand side only, not on how many threads run (one thread solves the
// bins one after the other). Not thread-safe: one solve at a time per object.
#pragma once

#include "solver_check/supernodal_tree.h"

#include <Eigen/Core>

#include <array>
#include <cstdint>
#include <vector>

namespace tissuemesh {

class SinglePrecisionFactor {
 public:
  /// Converts the factor's values to single precision in place (the header comment) and plans the
  /// two-thread split. `factor.values` and `factor.rows` must stay as they are while this object
  /// is used (until clear() or the next assign()); the other arrays are copied. Throws
  /// std::invalid_argument when the view is inconsistent (supernodes not covering the columns in
  /// order, a block not starting with its own columns, a row out of range, an unordered tree, a
  /// permutation that is not one), or std::bad_alloc; either way before changing the values or
  /// this object.
  void assign(const SupernodalFactorView& factor);
  bool empty() const { return n_ == 0; }
  /// Forgets the factor (its values stay converted) and releases the work vectors (empty() afterwards).
  void clear() { *this = SinglePrecisionFactor(); }
  /// z = (P^T L L^T P)^-1 r, computed in single precision, on `threads` threads (1 or 2 are used;
  /// the result is the same for any count).
  void solve(const Eigen::VectorXd& r, Eigen::VectorXd& z, int threads);
  /// Share of the factor's entries in the top part (solved by one thread), in [0, 1].
  double top_share() const { return top_share_; }

 private:
  /// assign() without the conversion: every check, the tree split and the work vectors.
  void plan(const SupernodalFactorView& factor);
  void forward(int s, float* y, float* outside, int first, int last, std::vector<float>& scratch) const;
  void backward(int s, float* y, std::vector<float>& scratch) const;

  int n_ = 0;
  std::vector<int> super_, pi_;
  const int* rows_ = nullptr;      ///< borrowed
  const float* values_ = nullptr;  ///< borrowed: the factor's array, converted
  std::vector<std::int64_t> px_;
  std::vector<int> perm_;
  std::array<std::vector<SubtreeRange>, 2> bins_;
  std::vector<int> top_;  ///< supernodes above the bins, increasing
  double top_share_ = 1.0;
  // Work vectors, kept between solves.
  std::vector<float> y_;
  std::array<std::vector<float>, 2> outside_;
  std::array<std::vector<float>, 2> scratch_;
};

}  // namespace tissuemesh
