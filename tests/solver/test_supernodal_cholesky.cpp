// SupernodalCholesky (solver_check/supernodal_cholesky.h): the factor of small supernodal
// structures against Eigen's dense Cholesky, with and without a diagonal shift, bit for bit the same
// on one and two threads; a matrix that is not positive definite; refusal of matrices that do not
// fit the factor's pattern.
#include "solver_check/supernodal_cholesky.h"

#include "supernodal_fixture.h"
#include "support/tolerances.h"

#include <Eigen/SparseCore>
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>
#include <vector>

namespace tissuemesh {
namespace {

using test::kRelativeRoundoff;
using SparseMatrix = Eigen::SparseMatrix<double>;

/// The lower triangle of the factor's matrix A (original numbering), its nonzeros only.
SparseMatrix lower(const Eigen::MatrixXd& A) {
  std::vector<Eigen::Triplet<double>> entries;
  for (int j = 0; j < A.cols(); ++j)
    for (int i = j; i < A.rows(); ++i)
      if (A(i, j) != 0.0) entries.emplace_back(i, j, A(i, j));
  SparseMatrix K(A.rows(), A.cols());
  K.setFromTriplets(entries.begin(), entries.end());
  return K;
}

/// The supernodal blocks of the dense factor of B (B's row/column k = A's perm[k]) in f's layout.
std::vector<double> blocks_of(const test::Factor& f, const Eigen::MatrixXd& B) {
  const Eigen::MatrixXd L = B.llt().matrixL();
  std::vector<double> values;
  for (std::size_t s = 0; s + 1 < f.super.size(); ++s)
    for (int k = f.super[s]; k < f.super[s + 1]; ++k)
      for (int p = f.pi[s]; p < f.pi[s + 1]; ++p) values.push_back(L(f.rows[p], k));
  return values;
}

/// Factorises f's matrix plus shift I on 1 and 2 threads: the blocks of the dense factor to
/// round-off, the same bits on both counts.
void expect_factor(test::Factor f, double shift) {
  const SparseMatrix K = lower(f.A);
  const int n = static_cast<int>(f.A.rows());
  Eigen::MatrixXd B(n, n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) B(i, j) = f.A(f.perm[i], f.perm[j]);
  B.diagonal().array() += shift;
  const std::vector<double> expected = blocks_of(f, B);
  SupernodalCholesky cholesky;
  cholesky.plan(f.view(), K);
  ASSERT_TRUE(cholesky.factorise(K, shift, 1));
  const std::vector<double> one = f.values;
  ASSERT_TRUE(cholesky.factorise(K, shift, 2));
  EXPECT_EQ(f.values, one);  // bitwise: the same on any thread count
  ASSERT_EQ(one.size(), expected.size());
  for (std::size_t i = 0; i < one.size(); ++i)
    EXPECT_NEAR(one[i], expected[i], kRelativeRoundoff * std::abs(expected[i]) + kRelativeRoundoff) << "entry " << i;
}

TEST(SupernodalCholesky, FactorisesAnArrowSplitBelowItsSeparator) {
  expect_factor(test::arrow(), 0.0);
  expect_factor(test::arrow(), 0.75);
}

TEST(SupernodalCholesky, FactorisesATwoLevelTreeWithUpdatesInsideABinAndIntoTheTop) {
  SupernodalCholesky planned;
  test::Factor f = test::two_levels();
  planned.plan(f.view(), lower(f.A));
  EXPECT_LT(planned.top_share(), 0.5);  // split: the bins hold most of the work
  expect_factor(test::two_levels(), 0.0);
  expect_factor(test::two_levels(), 2.5);
}

TEST(SupernodalCholesky, FactorisesAChainOnOneThread) {
  const Eigen::MatrixXd B = test::coupled(7, {{1, 0}, {6, 2}, {5, 3}});
  test::Factor f(B, {0, 7}, {0, 1, 2, 3, 4, 5, 6});
  SupernodalCholesky planned;
  planned.plan(f.view(), lower(f.A));
  EXPECT_EQ(planned.top_share(), 1.0);  // one supernode: nothing to split
  expect_factor(f, 0.0);
}

TEST(SupernodalCholesky, FactorisesAWideTopSupernodeByPanels) {
  // Two leaves of 10 under a 300-column separator (wider than kPanelledColumns = 256, so it is
  // factorised by panels of 128 on two threads) whose rows below reach the 10-column root: the
  // panels' row halves include those rows, and the last panel is narrower than 128.
  std::vector<std::pair<int, int>> couplings{{20, 0}, {25, 9}, {40, 10}, {300, 19}, {319, 20}, {200, 50},
                                             {320, 100}, {325, 319}, {329, 250}};
  for (int i = 1; i < 330; ++i)
    if (i != 10 && i != 20 && i != 320) couplings.emplace_back(i, i - 1);  // chains inside each supernode
  // Long-range couplings inside the separator and into the root: L's blocks fill in, so every
  // panel updates every column right of it (coupled() stays diagonally dominant: at most ~6
  // couplings per row against a diagonal of 13 or more there).
  for (int i = 20; i < 320; ++i) {
    const int j = 20 + (i * 37) % 300;
    if (j < i - 1) couplings.emplace_back(i, j);
    if (i % 3 == 0) couplings.emplace_back(320 + i % 10, i);
  }
  std::vector<int> perm(330);
  for (int i = 0; i < 330; ++i) perm[i] = (i * 7) % 330;  // 7 and 330 are coprime
  test::Factor f(test::coupled(330, couplings), {0, 10, 20, 320, 330}, perm);
  SupernodalCholesky planned;
  planned.plan(f.view(), lower(f.A));
  EXPECT_GT(planned.top_share(), 0.9);  // the wide separator is the top's
  expect_factor(f, 0.0);
  expect_factor(f, 1.5);
  // The same pattern with the separator's column 200 (in its second panel) not positive definite
  // while both leaves are: the failure is found in a panel, on 1 and 2 threads, and the next
  // matrix factorises again.
  const SparseMatrix K = lower(f.A);
  SparseMatrix indefinite = K;
  indefinite.coeffRef(f.perm[200], f.perm[200]) = -50.0;
  EXPECT_FALSE(planned.factorise(indefinite, 0.0, 2));
  EXPECT_FALSE(planned.factorise(indefinite, 0.0, 1));
  EXPECT_TRUE(planned.factorise(K, 0.0, 2));
}

TEST(SupernodalCholesky, ReportsAMatrixThatIsNotPositiveDefinite) {
  // coupled()'s diagonal is 8 .. 11.5 with off-diagonals of at most 1: a shift of -10 leaves
  // negative pivots in both bins and the top.
  test::Factor f = test::two_levels();
  const SparseMatrix K = lower(f.A);
  SupernodalCholesky cholesky;
  cholesky.plan(f.view(), K);
  EXPECT_FALSE(cholesky.factorise(K, -10.0, 2));
  EXPECT_FALSE(cholesky.factorise(K, -10.0, 1));
  EXPECT_TRUE(cholesky.factorise(K, 0.0, 2));  // and it recovers on the next matrix
}

TEST(SupernodalCholesky, RefusesAMatrixThatDoesNotFitTheFactor) {
  test::Factor f = test::arrow();
  const std::vector<double> before = f.values;
  auto refused = [&](const SparseMatrix& K) {
    SupernodalCholesky cholesky;
    EXPECT_THROW(cholesky.plan(f.view(), K), std::invalid_argument);
    EXPECT_TRUE(cholesky.empty());
    EXPECT_EQ(f.values, before);
  };
  // B's unknowns 3 (leaf {3,4}) and 0 (leaf {0,1,2}) are in different subtrees: no entry of L
  // couples them. A's numbering: perm[3] = 2, perm[0] = 4.
  SparseMatrix outside = lower(f.A);
  outside.coeffRef(4, 2) = 0.1;
  outside.makeCompressed();
  refused(outside);
  SparseMatrix upper = lower(f.A).transpose();
  upper.makeCompressed();
  refused(upper);
  refused(SparseMatrix(6, 6));
  SparseMatrix uncompressed = lower(f.A);
  uncompressed.uncompress();
  refused(uncompressed);
}

TEST(SupernodalCholesky, RefusesABlockWhoseRowsAreNotRowsOfTheAncestorItUpdates) {
  // two_levels(): supernode {0,1,2} has rows 0,1,2,6,13 and updates {6}, whose rows are 6,13,14.
  // With {6}'s rows 6,8,14 instead (and B's coupling (13,6) dropped, so K fits that pattern), the
  // update's row 13 has no place in {6}'s block.
  test::Factor f = test::two_levels();
  ASSERT_EQ(f.rows[f.pi[2] + 1], 13);
  f.rows[f.pi[2] + 1] = 8;
  Eigen::MatrixXd A = f.A;
  A(f.perm[13], f.perm[6]) = A(f.perm[6], f.perm[13]) = 0.0;
  SupernodalCholesky cholesky;
  try {
    cholesky.plan(f.view(), lower(A));
    ADD_FAILURE() << "accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("row 13 of supernode 0 is not a row of supernode 2"), std::string::npos)
        << e.what();
  }
  EXPECT_TRUE(cholesky.empty());
}

TEST(SupernodalCholesky, RefusesToFactoriseAMatrixOfAnotherPattern) {
  test::Factor f = test::arrow();
  const SparseMatrix K = lower(f.A);
  SupernodalCholesky cholesky;
  EXPECT_THROW(cholesky.factorise(K, 0.0, 1), std::invalid_argument);  // nothing planned
  cholesky.plan(f.view(), K);
  SparseMatrix other = K;
  other.coeffRef(4, 2) = 0.1;  // one entry more (outside L's pattern, see above)
  other.makeCompressed();
  EXPECT_THROW(cholesky.factorise(other, 0.0, 1), std::invalid_argument);
  SparseMatrix same_count = K;  // one entry moved: the diagonal entry (6, 6) dropped, (4, 2) added
  same_count.coeffRef(4, 2) = 0.1;
  same_count.prune([](Eigen::Index i, Eigen::Index j, double) { return !(i == 6 && j == 6); });
  same_count.makeCompressed();
  ASSERT_EQ(same_count.nonZeros(), K.nonZeros());
  EXPECT_THROW(cholesky.factorise(same_count, 0.0, 1), std::invalid_argument);
  EXPECT_TRUE(cholesky.factorise(K, 0.0, 1));
}

}  // namespace
}  // namespace tissuemesh
