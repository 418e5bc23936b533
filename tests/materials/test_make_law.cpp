// make_law: each MaterialLaw maps to its factory with the spec's parameters (round trip against
// the factory called directly), consistent specs give the spec's initial moduli, stresses scale
// with the unit system, and material_law_name gives the config names.
#include "core/errors.h"
#include "core/material_spec.h"
#include "materials/hyperelastic_law.h"
#include "materials/make_law.h"
#include "materials/tensor4.h"
#include "support/tolerances.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

using namespace tissuemesh;

namespace {

const Eigen::Matrix3d kI = Eigen::Matrix3d::Identity();

Eigen::Matrix3d sample_C() {
  Eigen::Matrix3d F;
  F << 1.15, 0.12, -0.05, 0.03, 0.92, 0.08, -0.04, 0.06, 1.01;
  return F.transpose() * F;
}

// Consistent specs (mu = 2 C10, mu = 2 (C10 + C01), mu = sum mu_i), tissue-like values in Pa.
MaterialSpec spec_of(MaterialLaw law) {
  MaterialSpec s;
  s.law = law;
  s.mu_Pa = 300.0;
  s.K_Pa = 50000.0;
  s.density_kg_m3 = 1000.0;
  switch (law) {
    case MaterialLaw::NeoHookean:
      s.C10_Pa = 150.0;
      break;
    case MaterialLaw::CompressibleNeoHookean:
      break;
    case MaterialLaw::MooneyRivlin:
      s.C10_Pa = 100.0;
      s.C01_Pa = 50.0;
      break;
    case MaterialLaw::Ogden:
      s.ogden = {{250.0, 2.0}, {50.0, -2.0}};
      break;
  }
  return s;
}

const MaterialLaw kAllLaws[] = {MaterialLaw::NeoHookean, MaterialLaw::CompressibleNeoHookean,
                                MaterialLaw::MooneyRivlin, MaterialLaw::Ogden};

// The factory each law must map to, called directly with the SI values.
std::unique_ptr<HyperelasticLaw> direct(const MaterialSpec& s) {
  switch (s.law) {
    case MaterialLaw::NeoHookean:
      return make_uncoupled_mooney_rivlin(s.C10_Pa, 0.0, s.K_Pa);
    case MaterialLaw::CompressibleNeoHookean:
      return make_compressible_neo_hookean(s.mu_Pa, s.K_Pa - 2.0 * s.mu_Pa / 3.0);
    case MaterialLaw::MooneyRivlin:
      return make_uncoupled_mooney_rivlin(s.C10_Pa, s.C01_Pa, s.K_Pa);
    case MaterialLaw::Ogden:
      return make_uncoupled_ogden({s.ogden[0].mu_Pa, s.ogden[1].mu_Pa}, {s.ogden[0].alpha, s.ogden[1].alpha},
                                  s.K_Pa);
  }
  return nullptr;
}

}  // namespace

TEST(MakeLaw, LawNamesAreTheConfigNames) {
  EXPECT_EQ(material_law_name(MaterialLaw::NeoHookean), "neo-hookean");
  EXPECT_EQ(material_law_name(MaterialLaw::CompressibleNeoHookean), "compressible-neo-hookean");
  EXPECT_EQ(material_law_name(MaterialLaw::MooneyRivlin), "mooney-rivlin");
  EXPECT_EQ(material_law_name(MaterialLaw::Ogden), "ogden");
}

TEST(MakeLaw, EachLawMapsToItsFactory) {
  const Eigen::Matrix3d C = sample_C();
  const double tol = test::kRelativeRoundoff;
  for (MaterialLaw l : kAllLaws) {
    const MaterialSpec s = spec_of(l);
    const auto law = make_law(s);
    const auto ref = direct(s);
    SCOPED_TRACE(material_law_name(l));
    EXPECT_EQ(law->name(), ref->name());
    EXPECT_NEAR(law->energy(C), ref->energy(C), tol * std::abs(ref->energy(C)));
    EXPECT_LT((law->pk2(C) - ref->pk2(C)).norm(), tol * ref->pk2(C).norm());
    EXPECT_LT((law->tangent(C) - ref->tangent(C)).norm(), tol * ref->tangent(C).norm());
  }
}

TEST(MakeLaw, ConsistentSpecsGiveTheirInitialModuli) {
  // At C = I every law is linear elasticity with the spec's mu and K: CC_1212 = mu,
  // CC_1111 = K + 4 mu / 3, CC_1122 = K - 2 mu / 3. Catches a parameter passed to the wrong slot.
  for (MaterialLaw l : kAllLaws) {
    const MaterialSpec s = spec_of(l);
    const Tangent6 T = make_law(s)->tangent(kI);
    const double tol = test::kRelativeRoundoff * s.K_Pa;
    SCOPED_TRACE(material_law_name(l));
    EXPECT_NEAR(T(3, 3), s.mu_Pa, tol);
    EXPECT_NEAR(T(0, 0), s.K_Pa + 4.0 * s.mu_Pa / 3.0, tol);
    EXPECT_NEAR(T(0, 1), s.lambda_Pa(), tol);
    EXPECT_LT(make_law(s)->pk2(kI).norm(), tol);
  }
}

TEST(MakeLaw, StressesScaleWithTheUnitSystem) {
  // Energy density, stress and tangent all have the unit of stress: mm-t-s (MPa) values are 1e-6
  // of SI, mm-kg-s (kPa) 1e-3. Ogden exponents are dimensionless: scaling them would break this.
  const Eigen::Matrix3d C = sample_C();
  const double tol = test::kRelativeRoundoff;
  for (MaterialLaw l : kAllLaws) {
    const MaterialSpec s = spec_of(l);
    const auto si = make_law(s, UnitSystem::SI);
    SCOPED_TRACE(material_law_name(l));
    for (const auto& [units, scale] : {std::pair{UnitSystem::MillimetreTonneSecond, 1e-6},
                                       std::pair{UnitSystem::MillimetreKilogramSecond, 1e-3}}) {
      const auto law = make_law(s, units);
      EXPECT_NEAR(law->energy(C), scale * si->energy(C), tol * scale * std::abs(si->energy(C)));
      EXPECT_LT((law->pk2(C) - scale * si->pk2(C)).norm(), tol * scale * si->pk2(C).norm());
      EXPECT_LT((law->tangent(C) - scale * si->tangent(C)).norm(), tol * scale * si->tangent(C).norm());
    }
  }
}

TEST(MakeLaw, InvalidOgdenTermsAreInputErrors) {
  MaterialSpec s = spec_of(MaterialLaw::Ogden);
  s.ogden.clear();
  EXPECT_THROW(make_law(s), InputError);
  s.ogden = {{100.0, 2.0}, {100.0, 2.0}, {100.0, 2.0}, {100.0, 2.0}};
  EXPECT_THROW(make_law(s), InputError);
  s.ogden = {{300.0, 0.0}};
  EXPECT_THROW(make_law(s), InputError);
}
