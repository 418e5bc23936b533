// Supernodal factors for the tests of solver_check/single_precision_factor.h and
// solver_check/supernodal_cholesky.h: dense Cholesky factors of small SPD matrices laid out as
// supernodes (solver_check/supernodal_tree.h), with a permutation, and two tree shapes.
#pragma once

#include "solver_check/supernodal_tree.h"

#include <Eigen/Cholesky>
#include <Eigen/Dense>

#include <utility>
#include <vector>

namespace tissuemesh::test {

/// A symmetric matrix B in elimination order with the given off-diagonal couplings, diagonally
/// dominant (SPD, condition number < 10).
inline Eigen::MatrixXd coupled(int n, const std::vector<std::pair<int, int>>& couplings) {
  Eigen::MatrixXd B = Eigen::MatrixXd::Zero(n, n);
  for (int i = 0; i < n; ++i) B(i, i) = 8.0 + 0.25 * i;
  double v = -1.0;
  for (const auto& [i, j] : couplings) {
    B(i, j) = B(j, i) = v;
    v = v < 0.0 ? 0.6 : -0.9;  // mixed signs and sizes
  }
  return B;
}

/// The Cholesky factor of B in the supernodal layout for the column partition `super`: each
/// supernode's rows are its columns and every later row where L has a nonzero in them. The matrix
/// solved is A with A(perm[i], perm[j]) = B(i, j).
struct Factor {
  std::vector<int> super, pi{0}, px{0}, rows, perm;
  std::vector<double> values;
  Eigen::MatrixXd A;

  Factor(const Eigen::MatrixXd& B, std::vector<int> super_, std::vector<int> perm_)
      : super(std::move(super_)), perm(std::move(perm_)) {
    const int n = static_cast<int>(B.rows());
    const Eigen::MatrixXd L = B.llt().matrixL();
    for (std::size_t s = 0; s + 1 < super.size(); ++s) {
      std::vector<int> block;
      for (int r = super[s]; r < n; ++r) {
        bool nonzero = r < super[s + 1];
        for (int k = super[s]; k < super[s + 1]; ++k) nonzero = nonzero || L(r, k) != 0.0;
        if (nonzero) block.push_back(r);
      }
      for (int k = super[s]; k < super[s + 1]; ++k)
        for (int r : block) values.push_back(L(r, k));
      rows.insert(rows.end(), block.begin(), block.end());
      pi.push_back(static_cast<int>(rows.size()));
      px.push_back(static_cast<int>(values.size()));
    }
    A.resize(n, n);
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) A(perm[i], perm[j]) = B(i, j);
  }
  /// Its view (a SinglePrecisionFactor assigned from it converts `values` in place).
  SupernodalFactorView view() {
    return {super.back(), static_cast<int>(super.size()) - 1, super.data(), pi.data(), px.data(), rows.data(),
            values.data(), perm.data()};
  }
  /// Entries of the supernodes' blocks.
  double entries() const { return static_cast<double>(px.back()); }
};

/// Two leaves {0,1,2} and {3,4} under a separator {5,6}: the arrow a nested-dissection ordering
/// makes. Blocks of 5 x 3, 4 x 2 and 2 x 2 entries: the leaves fill the bins, the separator's 4
/// of 27 entries are the top.
inline Factor arrow() {
  const Eigen::MatrixXd B = coupled(7, {{1, 0}, {2, 1}, {2, 0}, {4, 3}, {5, 0}, {6, 2}, {5, 3}, {6, 4}, {6, 5}});
  return Factor(B, {0, 3, 5, 7}, {4, 0, 6, 2, 5, 1, 3});
}

/// Two levels: under the top separator {13,14} a subtree of three supernodes ({0,1,2} and
/// {3,4,5} under {6}) and two leaves {7,8,9} and {10,11,12}. The subtree goes into one bin (its
/// updates of its own separator's row stay inside it, those of the top's rows go to the bin's
/// buffer), the two leaves together into the other.
inline Factor two_levels() {
  const Eigen::MatrixXd B = coupled(15, {{1, 0}, {2, 1}, {6, 0}, {6, 2}, {13, 1},            // {0,1,2}
                                         {4, 3}, {5, 4}, {6, 3}, {6, 5},                     // {3,4,5}
                                         {13, 6}, {14, 6},                                   // {6}
                                         {8, 7}, {9, 8}, {13, 7}, {14, 9},                   // {7,8,9}
                                         {11, 10}, {12, 11}, {14, 10}, {14, 12}, {14, 13}});  // {10,11,12}, top
  return Factor(B, {0, 3, 6, 7, 10, 13, 15}, {9, 3, 14, 0, 11, 6, 1, 12, 4, 7, 13, 2, 10, 5, 8});
}

}  // namespace tissuemesh::test
