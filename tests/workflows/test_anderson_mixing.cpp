// Anderson acceleration (workflows/anderson_mixing.h) on linear fixed points x = A x + b with a
// known solution: where plain damped iteration stalls on an eigenvalue of A near 1, the mixed
// iteration converges fifty times sooner (measured: about a hundred times); with memory 0 it is
// exactly the plain iteration.
#include "workflows/anderson_mixing.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>

#include <stdexcept>

namespace tissuemesh {
namespace {

/// A = Q diag(eig) Q^T, symmetric, with a fixed orthogonal Q; the fixed point is x* = 1.
struct Linear {
  Eigen::MatrixXd A;
  Eigen::VectorXd b, solution;
  explicit Linear(const Eigen::VectorXd& eig) {
    const int n = static_cast<int>(eig.size());
    Eigen::MatrixXd M(n, n);
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) M(i, j) = std::sin(1.0 + 3.0 * i + 7.0 * j);
    const Eigen::MatrixXd Q = Eigen::HouseholderQR<Eigen::MatrixXd>(M).householderQ();
    A = Q * eig.asDiagonal() * Q.transpose();
    solution = Eigen::VectorXd::Ones(n);
    b = solution - A * solution;
  }
  Eigen::VectorXd residual(const Eigen::VectorXd& x) const { return A * x + b - x; }
};

int iterations_to(const Linear& p, int memory, double beta, double tol, int max_it) {
  AndersonMixing mixing(memory);
  Eigen::VectorXd x = Eigen::VectorXd::Zero(p.b.size());
  for (int k = 0; k < max_it; ++k) {
    const Eigen::VectorXd f = p.residual(x);
    if ((x - p.solution).lpNorm<Eigen::Infinity>() <= tol) return k;
    x = mixing.next(x, f, beta);
  }
  return max_it;
}

TEST(AndersonMixing, ConvergesWherePlainIterationStalls) {
  // Twenty unknowns; two slow modes (0.996, 0.99) besides fast ones: the soft hanging mode of a
  // reference-state iteration in miniature.
  Eigen::VectorXd eig = Eigen::VectorXd::LinSpaced(20, -0.3, 0.3);
  eig[3] = 0.996;
  eig[11] = 0.99;
  const Linear p(eig);
  const int plain = iterations_to(p, 0, 1.0, 1e-8, 5000);
  const int mixed = iterations_to(p, 5, 1.0, 1e-8, 5000);
  std::cout << "[ workflow ] to 1e-8: plain " << plain << " iterations, Anderson(5) " << mixed << "\n";
  EXPECT_GT(plain, 2000);
  EXPECT_LE(mixed, plain / 50);
}

TEST(AndersonMixing, MemoryZeroIsPlainDampedIteration) {
  const Linear p(Eigen::VectorXd::LinSpaced(6, 0.1, 0.6));
  AndersonMixing mixing(0);
  Eigen::VectorXd x = Eigen::VectorXd::Zero(6), y = x;
  for (int k = 0; k < 10; ++k) {
    x = mixing.next(x, p.residual(x), 0.7);
    y = y + 0.7 * p.residual(y);
    EXPECT_EQ(x, y);
  }
  EXPECT_EQ(mixing.history(), 0);
}

TEST(AndersonMixing, RestartForgetsTheHistoryAndMemoryBoundsIt) {
  const Linear p(Eigen::VectorXd::LinSpaced(6, 0.1, 0.6));
  AndersonMixing mixing(3);
  Eigen::VectorXd x = Eigen::VectorXd::Zero(6);
  for (int k = 0; k < 6; ++k) x = mixing.next(x, p.residual(x), 1.0);
  EXPECT_EQ(mixing.history(), 3);
  mixing.restart();
  EXPECT_EQ(mixing.history(), 0);
  const Eigen::VectorXd f = p.residual(x);
  EXPECT_EQ(mixing.next(x, f, 0.5), x + 0.5 * f);  // a plain step after a restart
  EXPECT_THROW(mixing.next(x, Eigen::VectorXd::Zero(3), 1.0), std::invalid_argument);
  EXPECT_THROW(AndersonMixing(-1), std::invalid_argument);
}

}  // namespace
}  // namespace tissuemesh
