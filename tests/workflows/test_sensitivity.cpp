// Sensitivity estimators (workflows/sensitivity.h) and the Sobol' sequence behind them: on the
// Ishigami function (a = 7, b = 0.1, x uniform on [-pi, pi]^3) the Saltelli/Jansen estimators meet
// its analytic indices (Ishigami & Homma 1990; Saltelli et al. 2010: S = 0.3139, 0.4424, 0;
// ST = 0.5576, 0.4424, 0.2437); regression coefficients of a linear model are its exact shares.
#include "workflows/sensitivity.h"
#include "workflows/sobol_sequence.h"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

namespace tissuemesh {
namespace {

double ishigami(double x1, double x2, double x3) {
  return std::sin(x1) + 7.0 * std::sin(x2) * std::sin(x2) + 0.1 * std::pow(x3, 4) * std::sin(x1);
}

TEST(Sensitivity, SobolIndicesOfTheIshigamiFunction) {
  const int n = 1 << 14, d = 3;
  const std::vector<double> p = sobol_points(n, 2 * d, 42);  // A | B, side by side
  auto coord = [&](int i, int j) { return -M_PI + 2.0 * M_PI * p[static_cast<std::size_t>(i) * 2 * d + j]; };
  Eigen::VectorXd fa(n), fb(n);
  Eigen::MatrixXd fab(n, d);
  for (int i = 0; i < n; ++i) {
    double a[3], b[3];
    for (int j = 0; j < d; ++j) {
      a[j] = coord(i, j);
      b[j] = coord(i, d + j);
    }
    fa[i] = ishigami(a[0], a[1], a[2]);
    fb[i] = ishigami(b[0], b[1], b[2]);
    for (int j = 0; j < d; ++j) {
      double ab[3] = {a[0], a[1], a[2]};
      ab[j] = b[j];
      fab(i, j) = ishigami(ab[0], ab[1], ab[2]);
    }
  }
  const SobolIndices s = sobol_indices(fa, fb, fab);
  const double first[3] = {0.3139, 0.4424, 0.0}, total[3] = {0.5576, 0.4424, 0.2437};
  // 2^14 quasi-random base samples: the estimators' error is ~1e-3 (Saltelli 2010, fig. 2); 0.01.
  for (int j = 0; j < d; ++j) {
    std::cout << "[ sobol    ] x" << j + 1 << ": S " << s.first[j] << " (" << first[j] << "), ST " << s.total[j] << " ("
              << total[j] << ")\n";
    EXPECT_NEAR(s.first[j], first[j], 0.01);
    EXPECT_NEAR(s.total[j], total[j], 0.01);
  }
}

TEST(Sensitivity, RegressionCoefficientsOfALinearModelAreItsVarianceShares) {
  // y = 3 x1 + x2 (x3 inert) on a Sobol' design: SRC = 3 / sqrt(10), 1 / sqrt(10), 0; R^2 = 1.
  const int n = 256;
  const std::vector<double> p = sobol_points(n, 3, 7);
  Eigen::MatrixXd x(n, 3);
  Eigen::VectorXd y(n);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < 3; ++j) x(i, j) = p[static_cast<std::size_t>(i) * 3 + j];
    y[i] = 3.0 * x(i, 0) + x(i, 1);
  }
  const RegressionSensitivity r = standardised_regression(x, y);
  EXPECT_NEAR(r.r_squared, 1.0, 1e-12);
  // The design's sample variances differ from 1/12 by O(1/n): a few per cent at n = 256.
  EXPECT_NEAR(r.src[0], 3.0 / std::sqrt(10.0), 0.02);
  EXPECT_NEAR(r.src[1], 1.0 / std::sqrt(10.0), 0.02);
  EXPECT_NEAR(r.src[2], 0.0, 1e-9);
}

TEST(SobolSequence, FirstPointsAreTheKnownOnesAndStratify) {
  // Unshifted: 1/2, then (3/4, 1/4), (1/4, 3/4) in the first two dimensions (Joe & Kuo's table).
  const std::vector<double> p = sobol_points(4, 2, 0);
  EXPECT_EQ(p[0], 0.5);
  EXPECT_EQ(p[1], 0.5);
  EXPECT_EQ(p[2], 0.75);
  EXPECT_EQ(p[3], 0.25);
  EXPECT_EQ(p[4], 0.25);
  EXPECT_EQ(p[5], 0.75);
  // Every dimension of the first 2^k - 1 points (plus the skipped zero) hits each of 2^k bins once.
  const int k = 6, n = (1 << k) - 1;
  const std::vector<double> q = sobol_points(n, kMaxSobolDimensions, 0);
  for (int j = 0; j < kMaxSobolDimensions; ++j) {
    std::vector<int> bins(1 << k, 0);
    bins[0] = 1;  // the zero point
    for (int i = 0; i < n; ++i) ++bins[static_cast<int>(q[static_cast<std::size_t>(i) * kMaxSobolDimensions + j] * (1 << k))];
    for (int b : bins) EXPECT_EQ(b, 1) << "dimension " << j;
  }
  EXPECT_NE(sobol_points(4, 2, 1), sobol_points(4, 2, 2));
  EXPECT_THROW(sobol_points(4, kMaxSobolDimensions + 1, 0), std::invalid_argument);
}

}  // namespace
}  // namespace tissuemesh
