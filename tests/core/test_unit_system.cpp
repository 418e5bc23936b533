// Unit systems: the values of docs/formats.md ("Conventions shared by every file", units of model
// files) and the weight-per-volume consistency of every system.
#include "core/unit_system.h"
#include "support/test_helpers.h"
#include "support/tolerances.h"

#include <gtest/gtest.h>

using namespace tissuemesh;

namespace {
void expect_rel(double actual, double expected) {
  EXPECT_NEAR(actual, expected, test::kRelativeRoundoff * std::abs(expected)) << expected;
}
const UnitSystem kAll[] = {UnitSystem::SI, UnitSystem::MillimetreTonneSecond, UnitSystem::MillimetreKilogramSecond};
}  // namespace

TEST(UnitSystem, TableValuesForWaterAndGravity) {
  expect_rel(density_from_kg_per_m3(UnitSystem::MillimetreTonneSecond, 1000), 1e-9);
  expect_rel(density_from_kg_per_m3(UnitSystem::MillimetreKilogramSecond, 1000), 1e-6);
  expect_rel(acceleration_from_m_per_s2(UnitSystem::MillimetreTonneSecond, 9.81), 9810);
  expect_rel(stress_from_pascal(UnitSystem::MillimetreTonneSecond, 210e9), 210000);  // steel, N/mm^2
  expect_rel(stress_from_pascal(UnitSystem::MillimetreKilogramSecond, 5000), 5);     // 5 kPa
  expect_rel(length_from_mm(UnitSystem::SI, 70), 0.07);
  EXPECT_EQ(stress_unit(UnitSystem::MillimetreTonneSecond), "MPa");
}

TEST(UnitSystem, DensityTimesGravityIsTheWeightPerVolumeInEverySystem) {
  // Water weighs 9810 Pa per metre of depth; in any consistent system rho * g must equal that
  // stress per length (stress converted, divided by the length of one metre).
  for (UnitSystem s : kAll) {
    const double weight_per_volume = density_from_kg_per_m3(s, 1000) * acceleration_from_m_per_s2(s, 9.81);
    expect_rel(weight_per_volume, stress_from_pascal(s, 9810.0) / length_from_mm(s, 1000.0));
  }
}

TEST(UnitSystem, NamesRoundTripAndUnknownNamesAreRefused) {
  for (UnitSystem s : kAll) EXPECT_EQ(parse_unit_system(unit_system_name(s)), s);
  const std::string msg = test::input_error_of([] { parse_unit_system("cgs"); });
  EXPECT_NE(msg.find("'cgs'"), std::string::npos) << msg;
  EXPECT_NE(msg.find("mm-kg-s"), std::string::npos) << msg;
}

TEST(UnitSystem, ForceUnitIsStressTimesLengthSquared) {
  // One newton is 1 Pa on 1 m^2: converted stress times the squared length of one metre.
  for (UnitSystem s : kAll) {
    const double metre = length_from_mm(s, 1000.0);
    expect_rel(force_from_newton(s, 1.0), stress_from_pascal(s, 1.0) * metre * metre);
  }
  EXPECT_EQ(force_unit(UnitSystem::SI), "N");
  EXPECT_EQ(force_unit(UnitSystem::MillimetreTonneSecond), "N");
  EXPECT_EQ(force_unit(UnitSystem::MillimetreKilogramSecond), "mN");
  EXPECT_EQ(force_from_newton(UnitSystem::MillimetreKilogramSecond, 6.5), 6500.0);
}
