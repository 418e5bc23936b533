// SinglePrecisionFactor (solver_check/single_precision_factor.h): the single-precision solve with a
// supernodal factor built from a dense Cholesky factor, against a dense double solve; the
// two-thread split of its elimination tree; a result that does not depend on the number of
// threads; refusal of inconsistent factors before anything changes.
#include "solver_check/single_precision_factor.h"

#include "supernodal_fixture.h"
#include "support/tolerances.h"

#include <Eigen/Cholesky>
#include <Eigen/Dense>
#include <gtest/gtest.h>

#include <stdexcept>
#include <utility>
#include <vector>

namespace tissuemesh {
namespace {

using test::arrow;
using test::coupled;
using test::Factor;
using test::two_levels;

using test::kSinglePrecisionSolveRel;

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
