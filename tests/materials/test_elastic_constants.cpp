// Conversions between the usual forms of isotropic elastic constants, both ways, and refusals.
#include "core/errors.h"
#include "materials/elastic_constants.h"
#include "support/test_helpers.h"
#include "support/tolerances.h"

#include <gtest/gtest.h>

using namespace tissuemesh;

namespace {
void expect_rel(double actual, double expected) {
  EXPECT_NEAR(actual, expected, test::kRelativeRoundoff * std::abs(expected)) << expected;
}
}  // namespace

TEST(ElasticConstants, YoungPoissonFromTextbookFormulas) {
  // E = 3 kPa, nu = 0.49 (a breast-fat-like value): mu = E/(2(1+nu)), K = E/(3(1-2nu)),
  // lambda = E nu/((1+nu)(1-2nu)).
  const auto c = ElasticConstants::from_young_poisson(3.0, 0.49);
  expect_rel(c.shear_modulus(), 3.0 / 2.98);
  expect_rel(c.bulk_modulus(), 3.0 / 0.06);
  expect_rel(c.lame_lambda(), 3.0 * 0.49 / (1.49 * 0.02));
  expect_rel(c.young_modulus(), 3.0);
  expect_rel(c.poisson_ratio(), 0.49);
}

TEST(ElasticConstants, EveryFormRoundTrips) {
  const auto ref = ElasticConstants::from_young_poisson(15.0, 0.3);
  const double mu = ref.shear_modulus(), K = ref.bulk_modulus();
  for (const auto& c : {ElasticConstants::from_shear_bulk(mu, K), ElasticConstants::from_lame(mu, ref.lame_lambda()),
                        ElasticConstants::from_neo_hooke(ref.neo_hooke_C10(), ref.neo_hooke_D1()),
                        ElasticConstants::from_mooney_rivlin(0.3 * mu / 2, 0.7 * mu / 2, K),
                        ElasticConstants::from_young_poisson(ref.young_modulus(), ref.poisson_ratio())}) {
    expect_rel(c.shear_modulus(), mu);
    expect_rel(c.bulk_modulus(), K);
  }
  // Abaqus/CalculiX convention: mu = 2 C10, K = 2 / D1.
  expect_rel(ref.neo_hooke_C10(), mu / 2);
  expect_rel(ref.neo_hooke_D1(), 2 / K);
}

TEST(ElasticConstants, RefusalsSayWhy) {
  EXPECT_NE(test::input_error_of([] { ElasticConstants::from_young_poisson(1.0, 0.5); }).find("bulk modulus"),
            std::string::npos);
  EXPECT_NE(test::input_error_of([] { ElasticConstants::from_young_poisson(1.0, -1.0); }).find("above -1"),
            std::string::npos);
  EXPECT_NE(test::input_error_of([] { ElasticConstants::from_young_poisson(-2.0, 0.3); }).find("E = -2"),
            std::string::npos);
  EXPECT_NE(test::input_error_of([] { ElasticConstants::from_shear_bulk(0.0, 1.0); }).find("mu = 0"),
            std::string::npos);
  EXPECT_NE(test::input_error_of([] { ElasticConstants::from_shear_bulk(1.0, -3.0); }).find("K = -3"),
            std::string::npos);
  EXPECT_NE(test::input_error_of([] { ElasticConstants::from_lame(1.0, -1.0); }).find("bulk modulus"),
            std::string::npos);  // K = lambda + 2mu/3 < 0
  EXPECT_NE(test::input_error_of([] { ElasticConstants::from_neo_hooke(1.0, 0.0); }).find("D1"),
            std::string::npos);
  EXPECT_NE(test::input_error_of([] { ElasticConstants::from_mooney_rivlin(1.0, -1.0, 5.0); }).find("shear modulus"),
            std::string::npos);
}
