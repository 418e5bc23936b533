#include "workflows/sensitivity.h"

#include <Eigen/QR>

#include <cmath>
#include <stdexcept>

namespace tissuemesh {

namespace {

double standard_deviation(const Eigen::VectorXd& v) {
  const double mean = v.mean();
  return std::sqrt((v.array() - mean).square().sum() / static_cast<double>(v.size() - 1));
}

}  // namespace

RegressionSensitivity standardised_regression(const Eigen::MatrixXd& x, const Eigen::VectorXd& y) {
  const Eigen::Index n = x.rows(), d = x.cols();
  if (y.size() != n || n <= d + 1) throw std::invalid_argument("standardised_regression: need n > d + 1 samples");
  Eigen::MatrixXd design(n, d + 1);
  design.col(0).setOnes();
  design.rightCols(d) = x;
  const Eigen::VectorXd b = design.colPivHouseholderQr().solve(y);
  RegressionSensitivity out;
  const double sy = standard_deviation(y);
  out.src.assign(static_cast<std::size_t>(d), 0.0);
  if (!(sy > 0.0)) return out;
  for (Eigen::Index j = 0; j < d; ++j) out.src[j] = b[j + 1] * standard_deviation(x.col(j)) / sy;
  const Eigen::VectorXd fit = design * b;
  const double ss_res = (y - fit).squaredNorm(), ss_tot = (y.array() - y.mean()).square().sum();
  out.r_squared = 1.0 - ss_res / ss_tot;
  return out;
}

SobolIndices sobol_indices(const Eigen::VectorXd& f_a, const Eigen::VectorXd& f_b, const Eigen::MatrixXd& f_ab) {
  const Eigen::Index n = f_a.size(), d = f_ab.cols();
  if (f_b.size() != n || f_ab.rows() != n || n < 2) throw std::invalid_argument("sobol_indices: mismatched sizes");
  Eigen::VectorXd both(2 * n);
  both << f_a, f_b;
  const double mean = both.mean();
  const double variance = (both.array() - mean).square().sum() / static_cast<double>(2 * n - 1);
  SobolIndices out;
  out.first.assign(static_cast<std::size_t>(d), 0.0);
  out.total.assign(static_cast<std::size_t>(d), 0.0);
  if (!(variance > 0.0)) return out;
  for (Eigen::Index j = 0; j < d; ++j) {
    out.first[j] = (f_b.array() * (f_ab.col(j) - f_a).array()).mean() / variance;
    out.total[j] = (f_a - f_ab.col(j)).array().square().mean() / (2.0 * variance);
  }
  return out;
}

}  // namespace tissuemesh
