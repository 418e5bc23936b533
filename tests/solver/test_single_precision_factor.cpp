// SinglePrecisionFactor (solver_check/single_precision_factor.h): the single-precision solve with a
// hand-built supernodal factor against a dense double solve, the two-thread split of its
// elimination tree, and a result that does not depend on the number of threads.
#include "solver_check/single_precision_factor.h"

#include "support/tolerances.h"

#include <Eigen/Cholesky>
#include <Eigen/Dense>
#include <gtest/gtest.h>
#include <omp.h>

#include <stdexcept>
#include <vector>

namespace tissuemesh {
namespace {

using test::kSinglePrecisionSolveRel;

/// An "arrow" matrix B in elimination order: columns 0-2 and 3-4 are two independent blocks, both
/// coupled to the separator 5-6 only. Its Cholesky factor has no fill outside that pattern, so it
/// is three supernodes: {0,1,2} with rows 0,1,2,5,6; {3,4} with rows 3,4,5,6; {5,6}: two leaves
/// under one root, the tree a nested-dissection ordering produces. Diagonally dominant: SPD with a
/// small condition number.
Eigen::MatrixXd arrow_matrix() {
  Eigen::MatrixXd B = Eigen::MatrixXd::Zero(7, 7);
  auto couple = [&](int i, int j, double v) { B(i, j) = B(j, i) = v; };
  for (int i = 0; i < 7; ++i) B(i, i) = 6.0 + 0.5 * i;
  couple(1, 0, -1.0), couple(2, 1, -1.2), couple(2, 0, 0.3), couple(4, 3, -0.8);
  couple(5, 0, -0.7), couple(6, 2, 0.9), couple(5, 3, -1.1), couple(6, 4, 0.6), couple(6, 5, -0.5);
  return B;
}

/// The view of supernodal arrays (n = the last entry of `super`).
SupernodalFactorView view_of(const std::vector<int>& super, const std::vector<int>& pi, const std::vector<int>& px,
                             const std::vector<int>& rows, std::vector<double>& values, const int* perm) {
  SupernodalFactorView v;
  v.n = super.back();
  v.nsuper = static_cast<int>(super.size()) - 1;
  v.super = super.data();
  v.pi = pi.data();
  v.px = px.data();
  v.rows = rows.data();
  v.values = values.data();
  v.perm = perm;
  return v;
}

/// The factor of B in the supernodal layout (values column-major per supernode), and the
/// permutation perm[k] = the original index of row k: the matrix solved is A with
/// A(perm[i], perm[j]) = B(i, j).
struct Factor {
  std::vector<int> super{0, 3, 5, 7}, pi{0, 5, 9, 11}, px{0, 15, 23, 27};
  std::vector<int> rows{0, 1, 2, 5, 6, 3, 4, 5, 6, 5, 6};
  std::vector<double> values;
  std::vector<int> perm{4, 0, 6, 2, 5, 1, 3};
  Eigen::MatrixXd A;

  Factor() {
    const Eigen::MatrixXd B = arrow_matrix();
    const Eigen::MatrixXd L = B.llt().matrixL();
    for (int s = 0; s < 3; ++s)
      for (int k = super[s]; k < super[s + 1]; ++k)
        for (int i = pi[s]; i < pi[s + 1]; ++i) values.push_back(L(rows[i], k));
    A.resize(7, 7);
    for (int i = 0; i < 7; ++i)
      for (int j = 0; j < 7; ++j) A(perm[i], perm[j]) = B(i, j);
  }
  /// Its view: a SinglePrecisionFactor assigned from it converts `values` in place.
  SupernodalFactorView view() { return view_of(super, pi, px, rows, values, perm.data()); }
};

Eigen::VectorXd right_hand_side() { return Eigen::VectorXd::LinSpaced(7, -1.0, 2.5); }

TEST(SinglePrecisionFactor, SolvesThePermutedSystemToSinglePrecision) {
  Factor f;
  SinglePrecisionFactor factor;
  factor.assign(f.view());
  const Eigen::VectorXd b = right_hand_side();
  Eigen::VectorXd z;
  factor.solve(b, z);
  const Eigen::VectorXd exact = f.A.llt().solve(b);
  EXPECT_LT((z - exact).norm(), kSinglePrecisionSolveRel * exact.norm());
  // The same factor solves again from clean work vectors (the bins' buffers are reset).
  Eigen::VectorXd again;
  factor.solve(b, again);
  EXPECT_EQ(again, z);
}

TEST(SinglePrecisionFactor, SplitsTheTreeBelowTheSeparatorAndGivesTheSameResultOnAnyThreadCount) {
  Factor f;
  SinglePrecisionFactor factor;
  factor.assign(f.view());
  // The two leaves form the bins; the separator's 2 x 2 block (4 of the 27 entries) is the top.
  EXPECT_DOUBLE_EQ(factor.top_share(), 4.0 / 27.0);
  const int threads = omp_get_max_threads();
  Eigen::VectorXd one, two;
  omp_set_num_threads(1);
  factor.solve(right_hand_side(), one);
  omp_set_num_threads(2);
  factor.solve(right_hand_side(), two);
  omp_set_num_threads(threads);
  EXPECT_EQ(one, two);  // bitwise
}

TEST(SinglePrecisionFactor, ATreeWithoutBranchesIsSolvedByOneThread) {
  // One dense supernode (all 7 columns): nothing to split.
  const Eigen::MatrixXd B = arrow_matrix();
  const Eigen::MatrixXd L = B.llt().matrixL();
  std::vector<int> super{0, 7}, pi{0, 7}, px{0, 49}, rows{0, 1, 2, 3, 4, 5, 6};
  std::vector<double> values(L.data(), L.data() + 49);
  SinglePrecisionFactor factor;
  factor.assign(view_of(super, pi, px, rows, values, nullptr));
  EXPECT_EQ(factor.top_share(), 1.0);
  Eigen::VectorXd z;
  const Eigen::VectorXd b = right_hand_side(), exact = B.llt().solve(b);
  factor.solve(b, z);
  EXPECT_LT((z - exact).norm(), kSinglePrecisionSolveRel * exact.norm());
}

TEST(SinglePrecisionFactor, RefusesASupernodeThatDoesNotStartWithItsColumns) {
  Factor f;
  f.rows[5] = 4;  // supernode 1 (columns 3-4) would start with row 4
  f.rows[6] = 3;
  const std::vector<double> before = f.values;
  SinglePrecisionFactor factor;
  EXPECT_THROW(factor.assign(f.view()), std::invalid_argument);
  EXPECT_EQ(f.values, before);  // refused before the conversion in place
}

}  // namespace
}  // namespace tissuemesh
