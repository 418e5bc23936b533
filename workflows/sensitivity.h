// Sensitivity of a sweep's outputs to its parameters.
//
// Standardised regression coefficients (any design; Saltelli et al., "Global Sensitivity Analysis:
// The Primer", Wiley 2008, ch. 1): the least-squares fit y = b0 + sum_j b_j x_j, then
// SRC_j = b_j sd(x_j) / sd(y). For a model close to linear, SRC_j^2 is x_j's share of var(y), and
// R^2 tells how close to linear it is.
//
// Sobol' indices from the Saltelli design (A, B and the d matrices AB_j: A with column j from B;
// Saltelli et al., Comput. Phys. Commun. 181:259, 2010, table 2):
//   V     = variance of f over the 2N values f(A), f(B)
//   S_j   = mean( f(B) (f(AB_j) - f(A)) ) / V            first order (Saltelli 2010, eq. (b))
//   ST_j  = mean( (f(A) - f(AB_j))^2 ) / (2 V)           total (Jansen 1999, eq. (f))
#pragma once

#include <Eigen/Core>

#include <vector>

namespace tissuemesh {

struct RegressionSensitivity {
  std::vector<double> src;  ///< one per parameter (0 for a parameter that does not vary)
  double r_squared = 0.0;   ///< of the linear fit
};

/// x: n samples x d parameters, y: n outputs (n > d + 1, else std::invalid_argument).
RegressionSensitivity standardised_regression(const Eigen::MatrixXd& x, const Eigen::VectorXd& y);

struct SobolIndices {
  std::vector<double> first, total;  ///< one per parameter
};

/// f_a, f_b: N values each; f_ab: N x d (column j: f(AB_j)). std::invalid_argument for mismatched
/// sizes; all zero when V = 0 (a constant output).
SobolIndices sobol_indices(const Eigen::VectorXd& f_a, const Eigen::VectorXd& f_b, const Eigen::MatrixXd& f_ab);

}  // namespace tissuemesh
