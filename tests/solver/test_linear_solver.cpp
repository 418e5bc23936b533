// SparseSpdSolver (solver_check/linear_solver.h): direct and preconditioned solves to the
// requested residual, and the shifted (damped) step for a tangent that is not positive definite:
// which shift, how many attempts, and the attempts it saves (skipped unshifted try and rungs
// below the shift CG's direction of negative curvature proves too small, ladder started at the
// last working shift, the estimate's included, and ended at its largest rung from any start), a
// new factorisation once CG has cost half of one, the same factor whatever OpenBLAS's thread
// count, and the ordering of a node's unknowns together (DofMap::node_groups).
#include "solver_check/linear_solver.h"

#include "block_assembly.h"
#include "support/tolerances.h"

#include <gtest/gtest.h>

#include <dlfcn.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <stdexcept>
#include <vector>

namespace tissuemesh {
namespace {

using test::kRelativeRoundoff;
using SparseMatrix = Eigen::SparseMatrix<double>;

constexpr int kSize = 50;

/// Lower triangle of a tridiagonal block (diagonal `diagonal`, off-diagonal -1) on the first
/// kSize - 1 unknowns, and a last unknown coupled to nothing with diagonal `last`.
SparseMatrix matrix(double diagonal, double last) {
  std::vector<Eigen::Triplet<double>> entries;
  for (int i = 0; i < kSize - 1; ++i) {
    entries.emplace_back(i, i, diagonal);
    if (i + 1 < kSize - 1) entries.emplace_back(i + 1, i, -1.0);
  }
  entries.emplace_back(kSize - 1, kSize - 1, last);
  SparseMatrix K(kSize, kSize);
  K.setFromTriplets(entries.begin(), entries.end());
  return K;
}

double relative_residual(const SparseMatrix& K, const Eigen::VectorXd& x, const Eigen::VectorXd& b) {
  return (K.selfadjointView<Eigen::Lower>() * x - b).norm() / b.norm();
}

Eigen::VectorXd ramp() { return Eigen::VectorXd::LinSpaced(kSize, 1.0, 2.0); }

/// The shift s of a damped step x: (K + s I) x = b, so s = (b - K x) . x / |x|^2.
double damped_step_shift(const SparseMatrix& K, const Eigen::VectorXd& x, const Eigen::VectorXd& b) {
  return (b - K.selfadjointView<Eigen::Lower>() * x).dot(x) / x.squaredNorm();
}

/// Half a factorisation's cost in CG iterations as linear_solver.h documents it:
/// 0.5 factor_flops / (31 factor_entries) (kAgedShare, kFlopsPerStreamedEntry).
double half_factorisation_cost(const SparseSpdSolver& solver) {
  return 0.5 * solver.factor_flops() / (31.0 * solver.factor_entries());
}

class CholmodSolver : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!cholmod_available()) GTEST_SKIP() << "this build has no CHOLMOD";
  }
};

TEST_F(CholmodSolver, FactorisesOnceAndThenIteratesToTheRequestedResidual) {
  SparseSpdSolver solver(LinearSolverKind::Cholmod);
  const Eigen::VectorXd b = ramp();
  Eigen::VectorXd x;
  const SparseMatrix K1 = matrix(3.0, 1.0);
  ASSERT_TRUE(solver.solve(K1, b, x, 1e-4));
  EXPECT_LT(relative_residual(K1, x, b), kRelativeRoundoff);  // the direct solve
  EXPECT_EQ(solver.factorisations(), 1);
  EXPECT_EQ(solver.iterations(), 0);
  EXPECT_EQ(solver.preconditioner(), "none");
  // A nearby K: CG on the kept factorisation, to the requested residual and no further.
  const SparseMatrix K2 = matrix(3.3, 1.1);
  const double rtol = 1e-6;
  ASSERT_TRUE(solver.solve(K2, b, x, rtol));
  EXPECT_LE(relative_residual(K2, x, b), rtol);
  EXPECT_EQ(solver.factorisations(), 1);
  EXPECT_GT(solver.iterations(), 0);
  EXPECT_EQ(solver.preconditioner(), "the kept factorisation in single precision, 1 thread");
  EXPECT_EQ(solver.shifted_factorisations(), 0);
  EXPECT_EQ(solver.failed_factorisations(), 0);
}

// The indefinite K below has the single negative eigenvalue -0.01 (the uncoupled last unknown):
// the shift sigma * mean|K_ii| must exceed 0.01, which 1e-2 * 2.94 does and 1e-4 * 2.94 does not.
TEST_F(CholmodSolver, IndefiniteTangentGivesTheDampedStepOfTheSmallestWorkingShift) {
  SparseSpdSolver solver(LinearSolverKind::Cholmod);
  const SparseMatrix K = matrix(3.0, -0.01);
  const Eigen::VectorXd b = ramp();
  Eigen::VectorXd x;
  ASSERT_TRUE(solver.solve(K, b, x, 1e-4));
  // No factorisation to precondition with: unshifted, 1e-8, 1e-6 and 1e-4 fail, 1e-2 works.
  EXPECT_EQ(solver.failed_factorisations(), 4);
  EXPECT_EQ(solver.shifted_factorisations(), 1);
  EXPECT_EQ(solver.factorisations(), 1);
  const double shift = 1e-2 * K.diagonal().cwiseAbs().mean();
  SparseMatrix shifted = K;
  for (int i = 0; i < kSize; ++i) shifted.coeffRef(i, i) += shift;
  EXPECT_LT(relative_residual(shifted, x, b), kRelativeRoundoff);
  EXPECT_GT(b.dot(x), 0.0);  // a descent direction of the energy whose gradient is -b

  // The same K again: the shifted factor is not reused as a preconditioner; the unshifted try
  // fails and the ladder starts at the shift that worked, so nothing else is wasted.
  ASSERT_TRUE(solver.solve(K, b, x, 1e-4));
  EXPECT_EQ(solver.failed_factorisations(), 5);
  EXPECT_EQ(solver.shifted_factorisations(), 2);
  EXPECT_EQ(solver.iterations(), 0);
}

TEST_F(CholmodSolver, NegativeCurvatureInConjugateGradientsSkipsTheUnshiftedTry) {
  SparseSpdSolver solver(LinearSolverKind::Cholmod);
  Eigen::VectorXd b = Eigen::VectorXd::Zero(kSize), x;
  b[kSize - 1] = 1.0;
  ASSERT_TRUE(solver.solve(matrix(3.0, 1.0), b, x, 1e-4));
  ASSERT_EQ(solver.failed_factorisations(), 0);
  // The kept factor maps b to itself, and b^T K b = -0.01: CG's first direction proves K
  // indefinite, and K + s I too for any s below 0.01 (b^T b = 1). b is also K's lowest
  // eigenvector (eigenvalue -0.01), so the eigenvalue estimate is exact at once, and the shift is
  // the documented 5 x 0.01 (linear_solver.h): no unshifted try, no ladder rung, nothing fails.
  const SparseMatrix K = matrix(3.0, -0.01);
  ASSERT_TRUE(solver.solve(K, b, x, 1e-4));
  EXPECT_EQ(solver.failed_factorisations(), 0);
  EXPECT_EQ(solver.shifted_factorisations(), 1);
  EXPECT_EQ(solver.eigenvalue_iterations(), 0);
  const double expected = 1.0 / (-0.01 + 5.0 * 0.01);
  EXPECT_NEAR(x[kSize - 1], expected, kRelativeRoundoff * expected);
}

/// Lower triangle of the 1D Laplacian (2, -1) on kSize unknowns minus c I: eigenvalues
/// 2 - c - 2 cos(k pi / (kSize + 1)), k = 1 .. kSize, every eigenvector spread over all unknowns.
SparseMatrix laplacian(double c) {
  std::vector<Eigen::Triplet<double>> entries;
  for (int i = 0; i < kSize; ++i) {
    entries.emplace_back(i, i, 2.0 - c);
    if (i + 1 < kSize) entries.emplace_back(i + 1, i, -1.0);
  }
  SparseMatrix K(kSize, kSize);
  K.setFromTriplets(entries.begin(), entries.end());
  return K;
}

// A coupled negative mode: CG's direction of negative curvature is not the eigenvector, so LOBPCG
// has to iterate. The shift must lie between |lambda_min| (K + s I positive definite) and the
// documented 5 |lambda_min|; the ladder's rungs (1e-4 x mean|K_ii| = 2e-4 fails, 1e-2 x 2 = 0.02
// works, 16.6 |lambda_min|) would miss that window.
TEST_F(CholmodSolver, CoupledNegativeModeIsShiftedByItsEstimatedEigenvalue) {
  const double pi = std::acos(-1.0);
  const double c = 0.005;
  const double lowest = 2.0 - c - 2.0 * std::cos(pi / (kSize + 1));  // -0.00121
  const double second = 2.0 - c - 2.0 * std::cos(2.0 * pi / (kSize + 1));
  ASSERT_LT(lowest, 0.0);
  ASSERT_GT(second, 0.0);  // one negative eigenvalue
  SparseSpdSolver solver(LinearSolverKind::Cholmod);
  const Eigen::VectorXd b = ramp();
  Eigen::VectorXd x;
  ASSERT_TRUE(solver.solve(laplacian(-0.1), b, x, 1e-4));  // positive definite: the kept factor
  const SparseMatrix K = laplacian(c);
  ASSERT_TRUE(solver.solve(K, b, x, 1e-4));
  EXPECT_EQ(solver.failed_factorisations(), 0);
  EXPECT_EQ(solver.shifted_factorisations(), 1);
  EXPECT_GT(solver.eigenvalue_iterations(), 0);
  const double s = damped_step_shift(K, x, b);
  const Eigen::VectorXd Kx = K.selfadjointView<Eigen::Lower>() * x;
  EXPECT_GT(s, -lowest);
  EXPECT_LE(s, 5.0 * -lowest * (1.0 + kRelativeRoundoff));
  EXPECT_LT((Kx + s * x - b).norm(), kRelativeRoundoff * b.norm() / (s + lowest));
  EXPECT_GT(b.dot(x), 0.0);  // a descent direction of the energy whose gradient is -b
}

// After the estimate's shift worked, the same indefinite K again (as after a damped Newton step
// whose tangent is still indefinite): no kept factor, so the unshifted try fails, and the ladder
// starts at the estimate's shift, which works. A ladder restarted at 1e-8 x mean|K_ii| would also
// fail at 1e-8, 1e-6 and 1e-4 (|lambda_min| = 1.21e-3 on a diagonal of 1.995).
TEST_F(CholmodSolver, LadderStartsAtTheEstimatedShiftThatWorked) {
  SparseSpdSolver solver(LinearSolverKind::Cholmod);
  const Eigen::VectorXd b = ramp();
  Eigen::VectorXd x, again;
  ASSERT_TRUE(solver.solve(laplacian(-0.1), b, x, 1e-4));
  const SparseMatrix K = laplacian(0.005);
  ASSERT_TRUE(solver.solve(K, b, x, 1e-4));
  ASSERT_EQ(solver.shifted_factorisations(), 1);
  ASSERT_EQ(solver.failed_factorisations(), 0);
  ASSERT_TRUE(solver.solve(K, b, again, 1e-4));
  EXPECT_EQ(solver.failed_factorisations(), 1);  // the unshifted try only
  EXPECT_EQ(solver.shifted_factorisations(), 2);
  const double shift = damped_step_shift(K, x, b);
  EXPECT_NEAR(damped_step_shift(K, again, b), shift, kRelativeRoundoff * shift);
}

// From any start the ladder ends at its largest rung, 1e-2 x mean|K_ii|. The second solve leaves
// the estimate's shift (1.21e-3 .. 6.03e-3, i.e. 6.0e-4 .. 3.0e-3 of mean|K_ii|) as the ladder's
// start; the next K needs more than 0.01 (lambda_min = -0.01): the start fails, the next rung
// (100 x the start, above 1e-2) is clipped to 1e-2 x 1.986 = 0.0199, which works.
TEST_F(CholmodSolver, LadderEndsAtItsLargestShiftFromAnyStart) {
  const double pi = std::acos(-1.0);
  const double c = 2.0 - 2.0 * std::cos(pi / (kSize + 1)) + 0.01;  // lambda_min = -0.01
  ASSERT_GT(2.0 - c - 2.0 * std::cos(2.0 * pi / (kSize + 1)), 0.0);
  SparseSpdSolver solver(LinearSolverKind::Cholmod);
  const Eigen::VectorXd b = ramp();
  Eigen::VectorXd x;
  ASSERT_TRUE(solver.solve(laplacian(-0.1), b, x, 1e-4));
  ASSERT_TRUE(solver.solve(laplacian(0.005), b, x, 1e-4));
  ASSERT_EQ(solver.shifted_factorisations(), 1);
  const SparseMatrix K = laplacian(c);
  ASSERT_TRUE(solver.solve(K, b, x, 1e-4));
  EXPECT_EQ(solver.failed_factorisations(), 2);  // unshifted, then the start
  EXPECT_EQ(solver.shifted_factorisations(), 2);
  const double s = damped_step_shift(K, x, b);
  const double largest = 1e-2 * K.diagonal().cwiseAbs().mean();
  EXPECT_NEAR(s, largest, kRelativeRoundoff * largest);
}

// A K that no rung can make positive definite (lambda_min = -0.05; the top rung is
// 1e-2 x 2.94 = 0.0294): the unshifted try and the four rungs 1e-8, 1e-6, 1e-4, 1e-2 each fail
// once (1e-8 x 100^3 rounds to just below 1e-2 and is the top rung, not a fifth one), and the
// solve reports failure.
TEST_F(CholmodSolver, LadderTriesEachRungOnceAndThenGivesUp) {
  SparseSpdSolver solver(LinearSolverKind::Cholmod);
  Eigen::VectorXd x;
  EXPECT_FALSE(solver.solve(matrix(3.0, -0.05), ramp(), x, 1e-4));
  EXPECT_EQ(solver.failed_factorisations(), 5);
  EXPECT_EQ(solver.shifted_factorisations(), 0);
  EXPECT_EQ(solver.factorisations(), 0);
}

// CG on an old factor of a K far from the current one takes more iterations than half the
// documented estimate of a factorisation's cost (factor_flops / (31 factor_entries) iterations):
// the next solve factorises at once (a direct solve, no CG iteration), and the new factor then
// preconditions the solves after it.
TEST_F(CholmodSolver, FactorisesAtOnceAfterIterationsCostingHalfAFactorisation) {
  SparseSpdSolver solver(LinearSolverKind::Cholmod);
  const Eigen::VectorXd b = ramp();
  Eigen::VectorXd x;
  ASSERT_TRUE(solver.solve(matrix(3.0, 1.0), b, x, 1e-4));
  const SparseMatrix K = matrix(2.2, 4.0);
  ASSERT_TRUE(solver.solve(K, b, x, 1e-8));
  const int iterations = solver.iterations();
  ASSERT_EQ(solver.factorisations(), 1);
  ASSERT_GT(iterations, half_factorisation_cost(solver));
  ASSERT_TRUE(solver.solve(K, b, x, 1e-8));
  EXPECT_EQ(solver.factorisations(), 2);
  EXPECT_EQ(solver.iterations(), iterations);
  EXPECT_LT(relative_residual(K, x, b), kRelativeRoundoff);  // the direct solve
  // The fresh factor is K's own: the next solve iterates on it, to the requested residual.
  ASSERT_TRUE(solver.solve(matrix(2.21, 4.0), b, x, 1e-8));
  EXPECT_EQ(solver.factorisations(), 2);
  EXPECT_LE(relative_residual(matrix(2.21, 4.0), x, b), 1e-8);
}

/// Lower triangle of a dense SPD matrix: entry (i, j) = 1 / (1 + |i - j|) (a positive
/// semi-definite kernel) plus 2 on the diagonal, plus scale v_k v_k^T with v_k = cos((k + 1) i / n)
/// for each k < rank.
SparseMatrix dense(int n, int rank, double scale) {
  Eigen::MatrixXd A(n, n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) A(i, j) = 1.0 / (1.0 + std::abs(i - j)) + (i == j ? 2.0 : 0.0);
  for (int k = 0; k < rank; ++k) {
    Eigen::VectorXd v(n);
    for (int i = 0; i < n; ++i) v[i] = std::cos((k + 1.0) * i / n);
    A += scale * v * v.transpose();
  }
  return A.triangularView<Eigen::Lower>().toDenseMatrix().sparseView();
}

// With fill (a dense K of 300 unknowns) half a factorisation's estimated cost is a few CG
// iterations (3.2). The kept factor of K0 preconditions K0 plus a rank-r term, whose
// preconditioned matrix has r + 1 distinct eigenvalues: CG needs about r + 1 iterations (measured:
// 2 for r = 1, 4 for r = 2). A solve within half the cost keeps the factor (the next solve
// iterates on it); one beyond it makes the next solve factorise. The two cases pin the estimate
// between 2 and 4 iterations.
TEST_F(CholmodSolver, KeepsTheFactorWhileIterationsCostLessThanHalfAFactorisation) {
  const int n = 300;
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(n, 1.0, 2.0);
  const SparseMatrix K0 = dense(n, 0, 0.0);
  for (int rank : {1, 2}) {
    SCOPED_TRACE(rank);
    SparseSpdSolver solver(LinearSolverKind::Cholmod);
    Eigen::VectorXd x;
    ASSERT_TRUE(solver.solve(K0, b, x, 1e-6));
    const double half_cost = half_factorisation_cost(solver);
    const SparseMatrix K = dense(n, rank, 1.0);
    ASSERT_TRUE(solver.solve(K, b, x, 1e-6));
    const int iterations = solver.iterations();
    ASSERT_EQ(solver.factorisations(), 1);
    ASSERT_GT(iterations, 0);
    ASSERT_TRUE(solver.solve(K, b, x, 1e-6));
    if (rank == 1) {
      ASSERT_LE(iterations, half_cost);
      EXPECT_EQ(solver.factorisations(), 1);  // iterated on the kept factor again
      EXPECT_GT(solver.iterations(), iterations);
    } else {
      ASSERT_GT(iterations, half_cost);
      EXPECT_EQ(solver.factorisations(), 2);  // factorised at once
      EXPECT_EQ(solver.iterations(), iterations);
    }
    EXPECT_LE(relative_residual(K, x, b), 1e-6);
  }
}

// The factor of the tridiagonal K (49 unknowns) plus a decoupled one has no fill with a
// fill-reducing ordering: 49 + 48 off-diagonal + 1 = 98 entries. SimplicialLDLT (AMD) stores
// exactly those; CHOLMOD's supernodes may add explicit zeros, never fewer than K's lower triangle.
TEST(LinearSolverFactor, SizeIsReportedAfterTheFirstFactorisation) {
  const SparseMatrix K = matrix(3.0, 1.0);
  const Eigen::VectorXd b = ramp();
  Eigen::VectorXd x;
  SparseSpdSolver ldlt(LinearSolverKind::SimplicialLDLT);
  EXPECT_EQ(ldlt.factor_entries(), 0.0);
  ASSERT_TRUE(ldlt.solve(K, b, x, 1e-4));
  EXPECT_EQ(ldlt.factor_entries(), 98.0);
  EXPECT_EQ(ldlt.factor_flops(), 0.0);  // not counted by Eigen
  if (!cholmod_available()) return;
  SparseSpdSolver cholmod(LinearSolverKind::Cholmod);
  ASSERT_TRUE(cholmod.solve(K, b, x, 1e-4));
  EXPECT_GE(cholmod.factor_entries(), static_cast<double>(K.nonZeros()));
  EXPECT_LE(cholmod.factor_entries(), kSize * (kSize + 1) / 2.0);
  EXPECT_GT(cholmod.factor_flops(), 0.0);
}

/// Lower triangle of an SPD matrix on an n x n x n grid with 3 unknowns per node (7-point coupling
/// of each component, diagonally dominant): a factor with large dense supernodes, where OpenBLAS
/// runs its multithreaded code.
SparseMatrix grid_matrix(int n) {
  const auto index = [n](int i, int j, int k, int c) { return 3 * ((k * n + j) * n + i) + c; };
  std::vector<Eigen::Triplet<double>> entries;
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
        for (int c = 0; c < 3; ++c) {
          const int r = index(i, j, k, c);
          entries.emplace_back(r, r, 6.5 + 0.1 * c);
          if (i > 0) entries.emplace_back(r, index(i - 1, j, k, c), -1.0);
          if (j > 0) entries.emplace_back(r, index(i, j - 1, k, c), -1.0);
          if (k > 0) entries.emplace_back(r, index(i, j, k - 1, c), -1.0);
        }
  const int size = 3 * n * n * n;
  SparseMatrix K(size, size);
  K.setFromTriplets(entries.begin(), entries.end());
  return K;
}

TEST_F(CholmodSolver, SameFactorForAnyOpenBlasThreadCountBeforeIt) {
  using Get = int (*)();
  using Set = void (*)(int);
  const auto get = reinterpret_cast<Get>(dlsym(RTLD_DEFAULT, "openblas_get_num_threads"));
  const auto set = reinterpret_cast<Set>(dlsym(RTLD_DEFAULT, "openblas_set_num_threads"));
  if (!get || !set) GTEST_SKIP() << "CHOLMOD's BLAS is not OpenBLAS";
  if (const char* env = std::getenv("OPENBLAS_NUM_THREADS"); env && std::atoi(env) > 0)
    GTEST_SKIP() << "OPENBLAS_NUM_THREADS is set: the solver keeps it";
  const int original = get();
  const SparseMatrix K = grid_matrix(24);  // 41,472 unknowns
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(K.rows(), 1.0, 2.0);
  // The first solve of a solver factorises and solves directly: x follows the factor's bits.
  // `after`: the thread count set again once the solver exists, overriding its choice.
  const auto solve = [&](int threads, bool after) {
    set(threads);
    SparseSpdSolver solver(LinearSolverKind::Cholmod);
    EXPECT_EQ(get(), 1) << "the solver's own count";
    if (after) set(threads);
    Eigen::VectorXd x;
    EXPECT_TRUE(solver.solve(K, b, x, 0.0));
    EXPECT_EQ(solver.factorisations(), 1);
    return x;
  };
  // Two threads, not more: the suite runs on 2-core machines, where more only wait.
  const Eigen::VectorXd forced_one = solve(1, true), forced_two = solve(2, true);
  const Eigen::VectorXd one = solve(1, false), two = solve(2, false);
  set(original);
  EXPECT_LT(relative_residual(K, one, b), kRelativeRoundoff);
  ASSERT_EQ(one.size(), two.size());
  for (Eigen::Index i = 0; i < one.size(); ++i)
    if (one[i] != two[i]) {
      ADD_FAILURE() << "solutions after OpenBLAS thread counts 1 and 2 differ at unknown " << i;
      break;
    }
  // Only meaningful where the thread count does change the bits (it does with Debian 12's
  // OpenBLAS 0.3.21 on this matrix); elsewhere the equality above proves nothing.
  if (forced_one == forced_two) GTEST_SKIP() << "this OpenBLAS gives the same bits with 1 and 2 threads";
}

TEST_F(CholmodSolver, FactorisesTwoSubtreesAtOnceWithTheSameBitsAsOneThread) {
  if (const char* env = std::getenv("OPENBLAS_NUM_THREADS"); env && std::atoi(env) > 1)
    GTEST_SKIP() << "OPENBLAS_NUM_THREADS > 1: the factorisation runs on one thread";
  const SparseMatrix K = grid_matrix(12);  // 5,184 unknowns, 3 per grid node
  std::vector<int> nodes(K.rows());
  for (int j = 0; j < K.rows(); ++j) nodes[j] = j / 3;
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(K.rows(), 1.0, 2.0);
  const auto solve = [&](int threads) {
    SparseSpdSolver solver(LinearSolverKind::Cholmod, threads, nodes);
    Eigen::VectorXd x;
    EXPECT_TRUE(solver.solve(K, b, x, 0.0));
    EXPECT_EQ(solver.numeric_factorisation().rfind(threads == 2 ? "SupernodalCholesky, 2 threads (two subtrees"
                                                                : "SupernodalCholesky, 1 thread", 0),
              0u)
        << solver.numeric_factorisation();
    return x;
  };
  const Eigen::VectorXd two = solve(2), one = solve(1);
  EXPECT_LT(relative_residual(K, two, b), kRelativeRoundoff);
  EXPECT_TRUE(two == one) << "the factor's bits depend on the thread count";
  // Against an independent factorisation (Eigen's SimplicialLDLT, AMD ordering).
  SparseSpdSolver ldlt(LinearSolverKind::SimplicialLDLT);
  Eigen::VectorXd reference;
  ASSERT_TRUE(ldlt.solve(K, b, reference, 0.0));
  EXPECT_LT((two - reference).norm(), kRelativeRoundoff * reference.norm());
}

TEST_F(CholmodSolver, OrdersEachNodesUnknownsTogether) {
  // The block model's tangent: free nodes (3 unknowns), sliding ones (2) and fixed ones (none).
  test::BlockAssembly block;
  const DofMap& dofs = *block.dofs;
  // At the reference configuration, where the tangent is positive definite.
  ASSERT_TRUE(block.standard->assemble(Eigen::VectorXd::Zero(3 * dofs.num_nodes()), true).ok);
  const SparseMatrix& K = block.standard->tangent();
  const std::vector<int> groups = dofs.node_groups();
  ASSERT_EQ(static_cast<int>(groups.size()), dofs.num_free());
  int sliding = 0;
  for (int v = 0; v < dofs.num_nodes(); ++v) {
    sliding += dofs.count(v) == 2;
    for (int k = 0; k < dofs.count(v); ++k) EXPECT_EQ(groups[dofs.first(v) + k], groups[dofs.first(v)]);
  }
  ASSERT_GT(sliding, 0) << "the fixture should have sliding nodes";

  SparseSpdSolver solver(LinearSolverKind::Cholmod, 1, groups);
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(K.rows(), 1.0, 2.0);
  Eigen::VectorXd x;
  ASSERT_TRUE(solver.solve(K, b, x, 0.0));
  EXPECT_EQ(solver.shifted_factorisations(), 0);
  EXPECT_LT(relative_residual(K, x, b), kRelativeRoundoff);
  // Every group's unknowns follow each other in the factor, in their own order.
  const std::vector<int> order = solver.ordering();
  ASSERT_EQ(order.size(), groups.size());
  for (std::size_t k = 0; k < order.size();) {
    const int g = groups[order[k]];
    ASSERT_TRUE(order[k] == 0 || groups[order[k] - 1] != g) << "group " << g << " does not start at its first unknown";
    std::size_t next = k + 1;
    for (; next < order.size() && groups[order[next]] == g; ++next) ASSERT_EQ(order[next], order[next - 1] + 1);
    const std::size_t size = static_cast<std::size_t>(std::count(groups.begin(), groups.end(), g));
    ASSERT_EQ(next - k, size) << "group " << g << " is split";
    k = next;
  }
}

TEST(LinearSolverGroups, RefusesGroupsNotNumberedInOrder) {
  EXPECT_THROW(SparseSpdSolver(LinearSolverKind::Auto, 1, {1, 1}), std::invalid_argument);
  EXPECT_THROW(SparseSpdSolver(LinearSolverKind::Auto, 1, {0, 2}), std::invalid_argument);
  EXPECT_THROW(SparseSpdSolver(LinearSolverKind::Auto, 1, {0, 1, 0}), std::invalid_argument);
  EXPECT_NO_THROW(SparseSpdSolver(LinearSolverKind::Auto, 1, {0, 0, 1, 2, 2}));
}

}  // namespace
}  // namespace tissuemesh
