// Symmetric 4th-order tensor products in the Voigt layout of hyperelastic_law.h, for the laws.
#pragma once

#include "materials/hyperelastic_law.h"

namespace tissuemesh::tensor4 {

/// Voigt index pairs (11, 22, 33, 12, 23, 13).
constexpr int kVoigt[6][2] = {{0, 0}, {1, 1}, {2, 2}, {0, 1}, {1, 2}, {0, 2}};

/// (A (x) B)_ijkl = A_ij B_kl.
inline Tangent6 outer(const Eigen::Matrix3d& A, const Eigen::Matrix3d& B) {
  Tangent6 T;
  for (int a = 0; a < 6; ++a)
    for (int b = 0; b < 6; ++b) T(a, b) = A(kVoigt[a][0], kVoigt[a][1]) * B(kVoigt[b][0], kVoigt[b][1]);
  return T;
}

/// Symmetrised product (A (.) A)_ijkl = (A_ik A_jl + A_il A_jk) / 2; A = I gives the symmetric
/// identity, A = C^-1 gives -dC^-1/dC.
inline Tangent6 sym_product(const Eigen::Matrix3d& A) {
  Tangent6 T;
  for (int a = 0; a < 6; ++a)
    for (int b = 0; b < 6; ++b) {
      const int i = kVoigt[a][0], j = kVoigt[a][1], k = kVoigt[b][0], l = kVoigt[b][1];
      T(a, b) = 0.5 * (A(i, k) * A(j, l) + A(i, l) * A(j, k));
    }
  return T;
}

}  // namespace tissuemesh::tensor4
