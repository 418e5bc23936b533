// The `materials:` section: every parameter form converts to the same (mu, K), presets load with
// their sources, and every kind of bad input is refused with the key and the reason.
#include "core/errors.h"
#include "materials/material_config.h"
#include "support/test_helpers.h"
#include "support/test_paths.h"
#include "support/tolerances.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

using namespace tissuemesh;

namespace {

MaterialSpec parse(const std::string& yaml) {
  YamlMap map(YAML::Load(yaml), "materials.fat", "m.yaml");
  return parse_material(map);
}

std::string error_of(const std::string& yaml) {
  return test::input_error_of([&] { parse(yaml); });
}

void expect_moduli(const MaterialSpec& m, double mu, double K) {
  EXPECT_NEAR(m.mu_Pa, mu, mu * test::kRelativeRoundoff);
  EXPECT_NEAR(m.K_Pa, K, K * test::kRelativeRoundoff);
}

const std::string kRho = ", density: 1000 kg/m^3}";

}  // namespace

TEST(MaterialConfig, EveryParameterFormGivesTheSameModuli) {
  // mu = 300 Pa, K = 30 kPa: E = 9 K mu / (3K + mu), nu = (3K - 2mu) / (2(3K + mu)).
  const double mu = 300, K = 30e3;
  const double E = 9 * K * mu / (3 * K + mu), nu = (3 * K - 2 * mu) / (2 * (3 * K + mu));
  const double lambda = K - 2 * mu / 3;
  char buf[512];
  std::snprintf(buf, sizeof buf, "{law: neo-hookean, E: %.17g Pa, nu: %.17g%s", E, nu, kRho.c_str());
  expect_moduli(parse(buf), mu, K);
  expect_moduli(parse("{law: neo-hookean, mu: 0.3 kPa, K: 30 kPa" + kRho), mu, K);
  std::snprintf(buf, sizeof buf, "{law: neo-hookean, mu: 300 Pa, lambda: %.17g Pa%s", lambda, kRho.c_str());
  expect_moduli(parse(buf), mu, K);
  std::snprintf(buf, sizeof buf, "{law: neo-hookean, mu: 300 Pa, nu: %.17g%s", nu, kRho.c_str());
  expect_moduli(parse(buf), mu, K);
  expect_moduli(parse("{law: neo-hookean, C10: 150 Pa, D1: 0.066666666666666666 1/kPa" + kRho), mu, K);
  expect_moduli(parse("{law: neo-hookean, c1: 150 Pa, k: 0.03 MPa" + kRho), mu, K);
  const MaterialSpec mr = parse("{law: mooney-rivlin, c1: 100 Pa, c2: 50 Pa, k: 30 kPa" + kRho);
  expect_moduli(mr, mu, K);
  EXPECT_EQ(mr.C10_Pa, 100.0);
  EXPECT_EQ(mr.C01_Pa, 50.0);
  expect_moduli(parse("{law: mooney-rivlin, C10: 100 Pa, C01: 50 Pa, D1: 6.6666666666666667e-05 1/Pa" + kRho), mu, K);
  const MaterialSpec og = parse("{law: ogden, terms: [{mu: 200 Pa, alpha: 2}, {mu: 100 Pa, alpha: -2}], K: 30 kPa" + kRho);
  expect_moduli(og, mu, K);
  ASSERT_EQ(og.ogden.size(), 2u);
  EXPECT_EQ(og.ogden[1].alpha, -2.0);
  const MaterialSpec nh = parse("{law: neo-hookean, mu: 300 Pa, K: 30 kPa" + kRho);
  EXPECT_EQ(nh.C10_Pa, 150.0);
  EXPECT_EQ(nh.density_kg_m3, 1000.0);
}

TEST(MaterialConfig, ConversionsGoBothWays) {
  // Derived forms read back as input give the same material.
  const MaterialSpec a = parse("{law: compressible-neo-hookean, E: 5 kPa, nu: 0.49" + kRho);
  char buf[512];
  std::snprintf(buf, sizeof buf, "{law: compressible-neo-hookean, mu: %.17g Pa, lambda: %.17g Pa%s", a.mu_Pa,
                a.lambda_Pa(), kRho.c_str());
  const MaterialSpec b = parse(buf);
  EXPECT_NEAR(b.young_modulus_Pa(), 5000.0, 5000.0 * test::kRelativeRoundoff);
  EXPECT_NEAR(b.poisson_ratio(), 0.49, test::kRelativeRoundoff);
  std::snprintf(buf, sizeof buf, "{law: neo-hookean, C10: %.17g Pa, D1: %.17g 1/Pa%s", a.mu_Pa / 2, a.D1_per_Pa(),
                kRho.c_str());
  expect_moduli(parse(buf), a.mu_Pa, a.K_Pa);
}

TEST(MaterialConfig, BadParametersAreRefusedWithTheReason) {
  EXPECT_NE(error_of("{law: neo-hookean, E: 3 kPa, nu: 0.5" + kRho).find("give mu and a bulk modulus"), std::string::npos);
  EXPECT_NE(error_of("{law: neo-hookean, E: 3 kPa, nu: 0.5" + kRho).find("m.yaml: materials.fat"), std::string::npos);
  EXPECT_NE(error_of("{law: neo-hookean, mu: 0 Pa, K: 50 kPa" + kRho).find("must be positive"), std::string::npos);
  EXPECT_NE(error_of("{law: neo-hookean, mu: -1 Pa, K: 50 kPa" + kRho).find("shear modulus"), std::string::npos);
  EXPECT_NE(error_of("{law: hookean, mu: 1 Pa, K: 50 kPa" + kRho).find("unknown law 'hookean'"), std::string::npos);
  EXPECT_NE(error_of("{law: neo-hookean, mu: 150 Pa, K: 50 kPa, nu: 0.3" + kRho).find("do not form one parameter set"),
            std::string::npos);
  EXPECT_NE(error_of("{law: neo-hookean, mu: 150 Pa" + kRho).find("give exactly one of"), std::string::npos);
  EXPECT_NE(error_of("{law: neo-hookean, shear: 150 Pa, K: 1 kPa" + kRho).find("shear"), std::string::npos);
  EXPECT_NE(error_of("{law: neo-hookean, mu: 150, K: 50 kPa" + kRho).find("materials.fat.mu: '150' has no unit"),
            std::string::npos);
  EXPECT_NE(error_of("{law: neo-hookean, mu: 150 Pa, K: 50 kPa}").find("density: required"), std::string::npos);
  EXPECT_NE(error_of("{law: neo-hookean, mu: 150 Pa, K: 50 kPa, density: 1e-9 kg/m^3}").find("not a tissue density"),
            std::string::npos);
  EXPECT_NE(error_of("{law: neo-hookean, mu: 150 Pa, K: 50 kPa, density: 1000 Pa}").find("wrong kind of unit"),
            std::string::npos);
  EXPECT_NE(error_of("{law: ogden, terms: [{mu: 100 Pa, alpha: 0}], K: 1 kPa" + kRho).find("alpha != 0"),
            std::string::npos);
  EXPECT_NE(error_of("{law: ogden, terms: [{mu: -100 Pa, alpha: -2}], K: 1 kPa" + kRho).find("mu > 0"),
            std::string::npos);
  EXPECT_NE(error_of("{law: ogden, terms: [], K: 1 kPa" + kRho).find("1 to 3 terms"), std::string::npos);
  EXPECT_NE(error_of("{law: mooney-rivlin, C10: 100 Pa, C01: -100 Pa, K: 1 kPa" + kRho).find("C10 + C01"),
            std::string::npos);
}

TEST(MaterialConfig, PresetsLoadWithSourcesAndEntriesOverrideThem) {
  const auto dir = test::scratch_dir();
  std::filesystem::create_directories(dir / "materials");
  std::filesystem::copy_file(test::config_path("materials/ucl-niftysim-invivo.yaml"),
                             dir / "materials" / "ucl.yaml");
  YamlMap map(YAML::Load("{preset: materials/ucl.yaml, tumor: {law: neo-hookean, E: 9.6 kPa, nu: 0.49" + kRho + "}"),
              "materials", (dir / "cfg.yaml").string());
  const MaterialTable t = MaterialTable::from_yaml(map, (dir / "cfg.yaml").string());
  ASSERT_EQ(t.tissues.size(), 5u);
  EXPECT_EQ(t.tissues.at("fat").mu_Pa, 150.0);
  EXPECT_NE(t.tissues.at("fat").source.find("NiftySim"), std::string::npos);
  EXPECT_NEAR(t.tissues.at("tumor").young_modulus_Pa(), 9600.0, 9600.0 * test::kRelativeRoundoff);
  EXPECT_TRUE(t.tissues.at("tumor").source.empty());
  YamlMap missing(YAML::Load("{preset: nowhere.yaml}"), "materials", (dir / "cfg.yaml").string());
  EXPECT_NE(test::input_error_of([&] { MaterialTable::from_yaml(missing, (dir / "cfg.yaml").string()); })
                .find("nowhere.yaml"),
            std::string::npos);
}

TEST(MaterialConfig, ShippedPresetsLoadAndTheDemoUsesTheUclSet) {
  int n = 0;
  for (const auto& entry : std::filesystem::directory_iterator(std::string(TISSUEMESH_CONFIG_DIR) + "/materials")) {
    SCOPED_TRACE(entry.path().string());
    YamlMap map(YAML::Load("{preset: " + entry.path().string() + "}"), "materials", "t.yaml");
    const MaterialTable t = MaterialTable::from_yaml(map, "t.yaml");
    EXPECT_GE(t.tissues.size(), 3u);
    for (const auto& [name, m] : t.tissues) EXPECT_FALSE(m.source.empty()) << name << ": every value has a source";
    ++n;
  }
  EXPECT_GE(n, 3);
  YamlMap ucl(YAML::Load("{preset: materials/ucl-niftysim-invivo.yaml}"), "materials", "t.yaml");
  const MaterialTable file = MaterialTable::from_yaml(ucl, test::config_path("phantom.yaml"));
  YAML::Emitter a, b;
  file.to_yaml(a);
  MaterialTable::phantom_default().to_yaml(b);
  EXPECT_EQ(std::string(a.c_str()), std::string(b.c_str()));
}
