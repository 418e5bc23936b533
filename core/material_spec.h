// MaterialSpec: one tissue's constitutive law and parameters as plain data, in SI (Pa, kg/m^3).
//
// It is what a Model carries per tissue and what every writer and the solver read; the laws that
// evaluate it live in materials/ (make_law), the config parsing in materials/material_config.h.
// The four laws and their energies (docs/solver.md, "Laws"; Ī1 = J^(-2/3) I1, Ī2 = J^(-4/3) I2,
// λ̄a the deviatoric principal stretches):
//   NeoHookean              W = C10 (Ī1 - 3) + K/2 (J - 1)^2, C10 = mu/2
//                           (Abaqus/CalculiX NEO HOOKE with D1 = 2/K; FEBio Mooney-Rivlin, c2 = 0,
//                            pressure_model Abaqus — the same energy in both, exactly)
//   CompressibleNeoHookean  W = mu/2 (I1 - 3) - mu ln J + lambda/2 (ln J)^2, lambda = K - 2mu/3
//                           (FEBio neo-Hookean with E, v; SOFA NeoHookean "mu lambda")
//   MooneyRivlin            W = C10 (Ī1 - 3) + C01 (Ī2 - 3) + K/2 (J - 1)^2, mu = 2 (C10 + C01)
//   Ogden (1-3 terms)       W = sum_i 2 mu_i / alpha_i^2 (λ̄1^alpha_i + λ̄2^alpha_i + λ̄3^alpha_i - 3)
//                               + K/2 (J - 1)^2, mu = sum_i mu_i (Abaqus convention; FEBio
//                           c_i = 2 mu_i, m_i = alpha_i)
// `mu` is always the initial shear modulus and `K` the initial bulk modulus.
#pragma once

#include <string>
#include <vector>

namespace tissuemesh {

enum class MaterialLaw { NeoHookean, CompressibleNeoHookean, MooneyRivlin, Ogden };

/// "neo-hookean", "compressible-neo-hookean", "mooney-rivlin", "ogden" (the config names).
std::string material_law_name(MaterialLaw law);

struct OgdenTerm {
  double mu_Pa = 0.0;  ///< Abaqus mu_i (FEBio c_i = 2 mu_i)
  double alpha = 0.0;  ///< exponent, != 0
};

struct MaterialSpec {
  MaterialLaw law = MaterialLaw::NeoHookean;
  double mu_Pa = 0.0;    ///< initial shear modulus (every law)
  double K_Pa = 0.0;     ///< initial bulk modulus (every law)
  double C10_Pa = 0.0;   ///< NeoHookean (= mu/2), MooneyRivlin
  double C01_Pa = 0.0;   ///< MooneyRivlin only
  std::vector<OgdenTerm> ogden;  ///< Ogden only, 1 to 3 terms
  double density_kg_m3 = 0.0;    ///< mass density
  std::string source;            ///< where the values come from (preset citation), may be empty

  double lambda_Pa() const { return K_Pa - 2.0 * mu_Pa / 3.0; }
  double D1_per_Pa() const { return 2.0 / K_Pa; }
  double young_modulus_Pa() const { return 9.0 * K_Pa * mu_Pa / (3.0 * K_Pa + mu_Pa); }
  double poisson_ratio() const { return (3.0 * K_Pa - 2.0 * mu_Pa) / (2.0 * (3.0 * K_Pa + mu_Pa)); }
};

}  // namespace tissuemesh
