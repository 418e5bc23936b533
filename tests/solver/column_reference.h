// 1-D reference solutions of the solver verification suite (tests/solver/test_verification.cpp),
// computed here from closed-form principal stresses (Holzapfel, "Nonlinear Solid Mechanics",
// 2000), independently of materials/ and solver_check/, and checked against tabulated values in
// that test (docs/verification.md, "Solver: analytic references").
//
// Laws (core/material_spec.h), principal first Piola-Kirchhoff stress P_i = dW/d lambda_i of
// F = diag(l1, l2, l3), J = l1 l2 l3, I1 = l1^2 + l2^2 + l3^2:
//   CompressibleNeoHookean (lnJ):  P_i = mu (l_i - 1/l_i) + lambda_L ln J / l_i,  lambda_L = K - 2mu/3
//   NeoHookean ((J-1)^2):          P_i = mu J^(-2/3) (l_i - I1 / (3 l_i)) + K (J - 1) J / l_i
// Confined column: F = diag(1, 1, a(s)) along the column axis; equilibrium P_axial(a(s)) =
// sign * rho g s, s the distance from the free end (sign +1 hanging/tension, -1 standing/
// compression); the free end moves by Delta = int_0^L (a - 1) ds relative to the support.
// Uniaxial stress: F = diag(lambda, b, b) with P_lateral(lambda, b) = 0.
//
// Everything in consistent SI units (Pa, N/m^3, m). Root finding is bisection to the last bit
// (every P above increases strictly with its own stretch on the bracketed ranges), quadrature
// composite Gauss-Legendre: the results are exact to ~1e-14 relative.
#pragma once

#include <utility>
#include <vector>

#include "core/material_spec.h"

namespace tissuemesh::test {

/// Gauss-Legendre nodes and weights on [0, 1] (n >= 1): exact for polynomials of degree 2n - 1.
std::vector<std::pair<double, double>> gauss_legendre_01(int n);

/// P_1 of F = diag(l1, l2, l3) for law NeoHookean or CompressibleNeoHookean (std::invalid_argument
/// for the others), shear modulus mu and bulk modulus K.
double principal_pk1(MaterialLaw law, double mu, double K, double l1, double l2, double l3);

/// Homogeneous uniaxial stress at axial stretch lambda: lateral stretch b from P_2 = 0.
struct UniaxialState {
  double P11 = 0.0;              ///< first Piola-Kirchhoff axial stress
  double lateral_stretch = 0.0;  ///< b
  double J = 0.0;                ///< lambda b^2
};
UniaxialState uniaxial_stress(MaterialLaw law, double mu, double K, double lambda);

/// The confined column (exact 3D solution with frictionless lateral rollers).
class ConfinedColumn {
 public:
  /// rho_g: weight per volume (N/m^3); sign +1 hanging (tension), -1 standing (compression).
  /// The cumulative extension is tabulated on `panels` panels of 8-point Gauss-Legendre and
  /// interpolated by cubic Hermite (value and slope a - 1 exact at the panel ends): its error,
  /// h^4/384 max|a'''|, is ~1e-15 m for 400 panels on L = 0.1 m.
  ConfinedColumn(MaterialLaw law, double mu, double K, double rho_g, double length, int sign, int panels = 400);

  double length() const { return length_; }
  /// a(s), the axial stretch at distance s from the free end, 0 <= s <= L.
  double stretch(double s) const;
  /// U(s) = int_0^s (a - 1) ds (m), by interpolation of the table.
  double extension(double s) const;
  /// Delta = U(L): free end relative to the support (m; > 0 hanging, < 0 standing).
  double tip() const { return table_.back(); }

 private:
  double axial_stress(double a) const;
  MaterialLaw law_;
  double mu_, K_, rho_g_, length_;
  int sign_;
  std::vector<double> table_;  ///< U at the panel ends
  std::vector<double> slope_;  ///< a - 1 at the panel ends
};

}  // namespace tissuemesh::test
