// HyperelasticLaw: the one interface to the hyperelastic laws of core/material_spec.h, used by the
// built-in solver (solver_check/) and by the tests that check the writers' law mappings.
//
// A law is a strain-energy density W(C) per unit reference volume of the right Cauchy-Green tensor
// C = F^T F (symmetric positive definite). It gives the second Piola-Kirchhoff stress S = 2 dW/dC
// and the material tangent CC = 4 d2W/dC dC = 2 dS/dC, a symmetric 4th-order tensor returned in
// Voigt form with the order (11, 22, 33, 12, 23, 13) and no factor 2 on the shear entries
// (CC_voigt(a, b) = CC_ijkl for a = (ij), b = (kl)). Stresses are in the unit of the parameters.
// Laws do not throw on a non-positive det C: callers (the solver) must check J > 0 first.
#pragma once

#include <Eigen/Core>

#include <memory>
#include <string>
#include <vector>

namespace tissuemesh {

using Tangent6 = Eigen::Matrix<double, 6, 6>;

class HyperelasticLaw {
 public:
  virtual ~HyperelasticLaw() = default;
  /// e.g. "compressible neo-Hookean (ln J)".
  virtual std::string name() const = 0;
  virtual double energy(const Eigen::Matrix3d& C) const = 0;
  virtual Eigen::Matrix3d pk2(const Eigen::Matrix3d& C) const = 0;
  virtual Tangent6 tangent(const Eigen::Matrix3d& C) const = 0;
  /// W at C and, where the pointers are not null, S and CC: what an element kernel needs at a
  /// quadrature point, in one call, with the same values (bit for bit) as energy(), pk2() and
  /// tangent(). The default calls those three; a law overrides it to compute its invariants of C
  /// (inverse, determinant, powers of J) once instead of three times.
  virtual double evaluate(const Eigen::Matrix3d& C, Eigen::Matrix3d* S, Tangent6* CC) const {
    if (S) *S = pk2(C);
    if (CC) *CC = tangent(C);
    return energy(C);
  }

  /// The part of W that depends on J = sqrt(det C) alone, U(J), and its derivatives dU/dJ (the
  /// pressure it contributes, Cauchy sigma_vol = U'(J) I) and d2U/dJ2. Every law here is
  /// W = W_rest(C) + U(J) with the bulk stiffness in U and only shear-modulus-sized stiffness left
  /// in W_rest; the solver's nodal-pressure tet4 (solver_check/nodal_pressure.h) integrates U
  /// per node instead of per element.
  struct Volumetric {
    double U = 0.0, dU = 0.0, d2U = 0.0;
  };
  virtual Volumetric volumetric(double J) const = 0;
};

/// W = mu/2 (I1 - 3) - mu ln J + lambda/2 (ln J)^2 (FEBio `neo-Hookean`, SOFA `NeoHookean`);
/// volumetric part U = lambda/2 (ln J)^2.
std::unique_ptr<HyperelasticLaw> make_compressible_neo_hookean(double mu, double lambda);

/// Uncoupled Mooney-Rivlin W = C10 (I1bar - 3) + C01 (I2bar - 3) + K/2 (J - 1)^2
/// (Abaqus/CalculiX `MOONEY-RIVLIN` with D1 = 2/K; `NEO HOOKE` when C01 = 0; FEBio `Mooney-Rivlin`
/// with pressure_model Abaqus). I1bar = J^(-2/3) I1, I2bar = J^(-4/3) I2. Volumetric part
/// U = K/2 (J - 1)^2 (likewise for Ogden).
std::unique_ptr<HyperelasticLaw> make_uncoupled_mooney_rivlin(double C10, double C01, double K);

/// Uncoupled Ogden W = sum_i 2 mu_i / alpha_i^2 (λ̄1^alpha_i + λ̄2^alpha_i + λ̄3^alpha_i - 3)
/// + K/2 (J - 1)^2 with 1-3 terms (Abaqus/CalculiX `OGDEN, N=n` with D1 = 2/K; FEBio `Ogden`
/// with c_i = 2 mu_i, m_i = alpha_i, pressure_model Abaqus). Initial shear modulus sum mu_i.
std::unique_ptr<HyperelasticLaw> make_uncoupled_ogden(const std::vector<double>& mu,
                                                      const std::vector<double>& alpha, double K);

}  // namespace tissuemesh
