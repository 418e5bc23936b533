// ElasticConstants: the small-strain moduli of an isotropic material, given in any usual form and
// converted in this one place.
//
// Stored: shear modulus mu and bulk modulus K (both > 0), in the caller's stress unit (Pa, kPa or
// MPa: conversions are unit-free). Everything else is derived with the isotropic relations
//   E = 9 K mu / (3K + mu),  nu = (3K - 2mu) / (2(3K + mu)),  lambda = K - 2mu/3,
//   neo-Hookean / Mooney-Rivlin: C10 + C01 = mu/2, D1 = 2/K (Abaqus Analysis User's Guide,
//   "Hyperelastic behavior of rubberlike materials"; CalculiX CrunchiX User's Manual 2.20,
//   *HYPERELASTIC).
// Validation says why a value is refused: mu > 0, K > 0 (then -1 < nu < 0.5); nu >= 0.5 is
// refused with the advice to give a bulk modulus (incompressibility is approached by K >> mu).
#pragma once

#include <string>

namespace tissuemesh {

class ElasticConstants {
 public:
  /// Young's modulus E > 0 and Poisson's ratio -1 < nu < 0.5.
  static ElasticConstants from_young_poisson(double E, double nu);
  /// Shear modulus mu > 0 and bulk modulus K > 0.
  static ElasticConstants from_shear_bulk(double mu, double K);
  /// Lamé constants: shear modulus mu > 0 and lambda with K = lambda + 2mu/3 > 0.
  static ElasticConstants from_lame(double mu, double lambda);
  /// Abaqus/CalculiX NEO HOOKE: C10 > 0 and D1 > 0 (mu = 2 C10, K = 2/D1).
  static ElasticConstants from_neo_hooke(double C10, double D1);
  /// Mooney-Rivlin c1 (= C10), c2 (= C01), bulk modulus k: mu = 2(c1 + c2) > 0, K = k > 0.
  static ElasticConstants from_mooney_rivlin(double c1, double c2, double k);

  double shear_modulus() const { return mu_; }
  double bulk_modulus() const { return K_; }
  double young_modulus() const { return 9.0 * K_ * mu_ / (3.0 * K_ + mu_); }
  double poisson_ratio() const { return (3.0 * K_ - 2.0 * mu_) / (2.0 * (3.0 * K_ + mu_)); }
  double lame_lambda() const { return K_ - 2.0 * mu_ / 3.0; }
  /// Abaqus/CalculiX NEO HOOKE coefficients.
  double neo_hooke_C10() const { return mu_ / 2.0; }
  double neo_hooke_D1() const { return 2.0 / K_; }

 private:
  ElasticConstants(double mu, double K, const std::string& given);
  double mu_ = 0.0;
  double K_ = 0.0;
};

}  // namespace tissuemesh
