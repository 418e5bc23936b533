// Finite-difference helpers for the hyperelastic-law tests.
#pragma once

#include <Eigen/Core>

namespace tissuemesh::test {

/// Symmetric perturbation of C in the (i, j) component by h (split over ij and ji), so that a
/// central difference in h gives dW/dC_ij + dW/dC_ji = the Voigt-convention derivative.
inline Eigen::Matrix3d bump(const Eigen::Matrix3d& C, int i, int j, double h) {
  Eigen::Matrix3d D = C;
  if (i == j) {
    D(i, i) += h;
  } else {
    D(i, j) += h / 2;
    D(j, i) += h / 2;
  }
  return D;
}

}  // namespace tissuemesh::test
