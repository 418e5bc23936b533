// SinglePrecisionFactor (solver_check/single_precision_factor.h): the single-precision solve with a
// supernodal factor built from a dense Cholesky factor, against a dense double solve; the
// two-thread split of its elimination tree; a result that does not depend on the number of
// threads; refusal of inconsistent factors before anything changes.
#include "solver_check/single_precision_factor.h"

#include "support/tolerances.h"

#include <Eigen/Cholesky>
#include <Eigen/Dense>
#include <gtest/gtest.h>

#include <stdexcept>
#include <utility>
#include <vector>

namespace tissuemesh {
namespace {

using test::kSinglePrecisionSolveRel;

/// A symmetric matrix B in elimination order with the given off-diagonal couplings, diagonally
/// dominant (SPD, condition number < 10).
Eigen::MatrixXd coupled(int n, const std::vector<std::pair<int, int>>& couplings) {
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
  /// Its view: a SinglePrecisionFactor assigned from it converts `values` in place.
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
Factor arrow() {
  const Eigen::MatrixXd B = coupled(7, {{1, 0}, {2, 1}, {2, 0}, {4, 3}, {5, 0}, {6, 2}, {5, 3}, {6, 4}, {6, 5}});
  return Factor(B, {0, 3, 5, 7}, {4, 0, 6, 2, 5, 1, 3});
}

/// Two levels: under the top separator {13,14} a subtree of three supernodes ({0,1,2} and
/// {3,4,5} under {6}) and two leaves {7,8,9} and {10,11,12}. The subtree goes into one bin (its
/// updates of its own separator's row stay inside it, those of the top's rows go to the bin's
/// buffer), the two leaves together into the other.
Factor two_levels() {
  const Eigen::MatrixXd B = coupled(15, {{1, 0}, {2, 1}, {6, 0}, {6, 2}, {13, 1},            // {0,1,2}
                                         {4, 3}, {5, 4}, {6, 3}, {6, 5},                     // {3,4,5}
                                         {13, 6}, {14, 6},                                   // {6}
                                         {8, 7}, {9, 8}, {13, 7}, {14, 9},                   // {7,8,9}
                                         {11, 10}, {12, 11}, {14, 10}, {14, 12}, {14, 13}});  // {10,11,12}, top
  return Factor(B, {0, 3, 6, 7, 10, 13, 15}, {9, 3, 14, 0, 11, 6, 1, 12, 4, 7, 13, 2, 10, 5, 8});
}

Eigen::VectorXd right_hand_side(int n) { return Eigen::VectorXd::LinSpaced(n, -1.0, 2.5); }

void expect_solves(Factor f, double top_entries) {
  const Eigen::VectorXd b = right_hand_side(static_cast<int>(f.A.rows()));
  const Eigen::VectorXd exact = f.A.llt().solve(b);
  SinglePrecisionFactor factor;
  factor.assign(f.view());
  EXPECT_DOUBLE_EQ(factor.top_share(), top_entries / f.entries());
  Eigen::VectorXd one, two, again;
  factor.solve(b, one, 1);
  factor.solve(b, two, 2);
  factor.solve(b, again, 2);  // from clean work vectors: the bins' buffers were reset
  EXPECT_LT((two - exact).norm(), kSinglePrecisionSolveRel * exact.norm());
  EXPECT_EQ(one, two);  // bitwise: the same on any thread count
  EXPECT_EQ(again, two);
}

TEST(SinglePrecisionFactor, SolvesAnArrowSplitBelowItsSeparator) { expect_solves(arrow(), 4.0); }

TEST(SinglePrecisionFactor, SolvesATwoLevelTreeWithASubtreeInOneBinAndTwoLeavesInTheOther) {
  // Blocks: {0,1,2} rows 0,1,2,6,13 (15); {3,4,5} rows 3,4,5,6 (12); {6} rows 6,13,14 (3);
  // {7,8,9} rows 7,8,9,13,14 (15); {10,11,12} rows 10,11,12,14 (12); top {13,14} (4): bins of 30
  // and 27 entries, the top 4 of 61.
  Factor f = two_levels();
  ASSERT_EQ(f.entries(), 61.0);
  expect_solves(std::move(f), 4.0);
}

TEST(SinglePrecisionFactor, OpensASubtreeWhenThatEvensTheBinsAtLowerCost) {
  // Leaves {0,1,2} and {3,4,5} under {6} (12 + 12 + 2 entries), a small leaf {7} (2), all under
  // the top {8,9} (4): 32 entries. Split below the top: bins 26 / 2, estimated time 4 + 26. Opening
  // {6} too: bins {0,1,2} + {7} / {3,4,5}, 14 / 12, time 6 + 14: the better split, kept, with a
  // bin of two subtrees.
  const Eigen::MatrixXd B = coupled(10, {{1, 0}, {2, 1}, {6, 0}, {4, 3}, {5, 4}, {6, 5}, {8, 6}, {9, 7}, {9, 8}});
  Factor f(B, {0, 3, 6, 7, 8, 10}, {3, 8, 1, 6, 0, 9, 2, 7, 5, 4});
  ASSERT_EQ(f.entries(), 32.0);
  expect_solves(std::move(f), 6.0);
}

TEST(SinglePrecisionFactor, ATreeNotInPostorderIsSolvedByOneThread) {
  // Columns 0 and 2 under 3, column 1 under 4, both under 5: the subtree of 3 is {0, 2, 3}, not a
  // contiguous range, so the bins (ranges of supernodes) cannot hold it: no split.
  const Eigen::MatrixXd B = coupled(6, {{3, 0}, {4, 1}, {3, 2}, {5, 3}, {5, 4}});
  const Factor f(B, {0, 1, 2, 3, 4, 5, 6}, {2, 5, 0, 4, 1, 3});
  expect_solves(f, f.entries());
}

TEST(SinglePrecisionFactor, ATreeWithoutBranchesIsSolvedByOneThread) {
  // One dense supernode: nothing to split, all of it is the top.
  const Eigen::MatrixXd B = coupled(7, {{1, 0}, {6, 2}, {5, 3}});
  expect_solves(Factor(B, {0, 7}, {0, 1, 2, 3, 4, 5, 6}), 49.0);
}

TEST(SinglePrecisionFactor, RefusesAnInconsistentFactorBeforeChangingAnything) {
  auto refused = [](Factor f) {
    const std::vector<double> before = f.values;
    SinglePrecisionFactor factor;
    EXPECT_THROW(factor.assign(f.view()), std::invalid_argument);
    EXPECT_TRUE(factor.empty());
    EXPECT_EQ(f.values, before);  // not converted
  };
  Factor not_own_columns = arrow();
  std::swap(not_own_columns.rows[5], not_own_columns.rows[6]);  // supernode {3,4} starts with row 4
  refused(not_own_columns);
  Factor row_out_of_range = arrow();
  row_out_of_range.rows[4] = 7;  // supernode {0,1,2}'s last row 6 -> 7 (n = 7)
  refused(row_out_of_range);
  Factor row_not_below = arrow();
  row_not_below.rows[3] = 1;  // an off-diagonal row of {0,1,2} among its own columns
  refused(row_not_below);
  Factor not_a_permutation = arrow();
  not_a_permutation.perm[0] = not_a_permutation.perm[1];
  refused(not_a_permutation);
  Factor short_cover = arrow();
  short_cover.super.back() = 6;  // the supernodes end before the last column
  refused(short_cover);
}

}  // namespace
}  // namespace tissuemesh
