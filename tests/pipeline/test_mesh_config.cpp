#include "core/errors.h"
#include "pipeline/mesh_config.h"
#include "support/test_paths.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

using namespace tissuemesh;

namespace {
std::string error_of(const std::string& yaml) {
  try {
    MeshConfig::parse(YAML::Load(yaml), "t.yaml");
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

// The meshing part of a shipped whole-pipeline config (its materials/model/export sections are
// read by the program's job config and checked by the CLI tests).
MeshConfig meshing_part(const std::string& path) {
  YamlMap top(load_yaml_file(path), "", path);
  return MeshConfig::from_top(top);
}
}  // namespace

TEST(MeshConfig, ShippedPhantomConfigEqualsBuiltInDefaults) {
  // `tissuemesh demo` without -c uses the built-in config; configs/phantom.yaml documents it.
  const MeshConfig file = meshing_part(test::config_path("phantom.yaml"));
  EXPECT_EQ(file.to_yaml(), MeshConfig::phantom_default().to_yaml());
}

TEST(MeshConfig, EveryShippedConfigLoads) {
  int n = 0;
  for (const auto& entry : std::filesystem::directory_iterator(TISSUEMESH_CONFIG_DIR)) {
    if (entry.path().extension() != ".yaml") continue;
    SCOPED_TRACE(entry.path().string());
    EXPECT_NO_THROW(meshing_part(entry.path().string()));
    ++n;
  }
  EXPECT_GE(n, 2);
}

TEST(MeshConfig, EffectiveConfigRoundTrips) {
  const MeshConfig c = meshing_part(test::config_path("breast-generic.yaml"));
  const MeshConfig again = MeshConfig::parse(YAML::Load(c.to_yaml()), "effective");
  EXPECT_EQ(again.to_yaml(), c.to_yaml());
}

TEST(MeshConfig, ErrorsNameFileKeyAndValue) {
  const std::string tissues = "tissues: [{name: fat, labels: [1]}]\n";
  EXPECT_NE(error_of(tissues + "pipline: direct").find("t.yaml: pipline: unknown key"), std::string::npos);
  EXPECT_NE(error_of(tissues + "pipeline: magic").find("unknown pipeline 'magic'"), std::string::npos);
  EXPECT_NE(error_of(tissues + "direct: {cell_size_mm: -2}").find("direct.cell_size_mm: must be positive"),
            std::string::npos);
  EXPECT_NE(error_of(tissues + "direct: {facet_angle_deg: 40}").find("direct.facet_angle_deg"), std::string::npos);
  EXPECT_NE(error_of(tissues + "direct: {cell_size_per_tissue_mm: {fat: 0}}").find("cell_size_per_tissue_mm.fat"),
            std::string::npos);
  EXPECT_NE(error_of(tissues + "phantom: {tumor_diameter_mm: -1}").find("tumor_diameter_mm"), std::string::npos);
  EXPECT_NE(error_of(tissues + "phantom: {sede: 3}").find("phantom.sede"), std::string::npos);
  EXPECT_NE(error_of(tissues + "surface: {mean_quality_passes: 21}").find("surface.mean_quality_passes: must be in 0..20"),
            std::string::npos);
  EXPECT_NE(error_of("pipeline: direct").find("tissues"), std::string::npos);
}

TEST(MeshConfig, InvalidYamlNamesTheLine) {
  const auto path = test::scratch_dir() / "broken.yaml";
  std::ofstream(path) << "pipeline: direct\ntissues: [{name: fat, labels: [1]}\n";
  try {
    MeshConfig::load(path.string());
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("broken.yaml: invalid YAML at line"), std::string::npos) << e.what();
  }
}

TEST(MeshChecks, VolumeToleranceIsReadCheckedAndPrinted) {
  const std::string tissues = "tissues: [{name: fat, labels: [1]}]\n";
  const MeshConfig c = MeshConfig::parse(YAML::Load(tissues + "checks: {volume_tolerance_percent: 3}"), "t.yaml");
  EXPECT_EQ(c.checks.volume_tolerance_percent, 3.0);
  EXPECT_NE(c.to_yaml().find("volume_tolerance_percent: 3"), std::string::npos) << c.to_yaml();
  EXPECT_EQ(MeshConfig::parse(YAML::Load(tissues), "t.yaml").checks.volume_tolerance_percent, 5.0);
  for (const char* bad : {"checks: {volume_tolerance_percent: 0}", "checks: {volume_tolerance_percent: -1}",
                          "checks: {volume_tolerance: 3}"}) {
    try {
      MeshConfig::parse(YAML::Load(tissues + bad), "t.yaml");
      ADD_FAILURE() << "accepted: " << bad;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("checks"), std::string::npos) << e.what();
    }
  }
}

TEST(MeshChecks, TissuesOutsideTheVolumeToleranceAreNamedWithTheirError) {
  QualityReport q;
  const auto tissue = [](const char* name, double volume, double reference) {
    TissueQuality t;
    t.name = name;
    t.volume_mm3 = volume;
    t.reference_volume_mm3 = reference;
    t.volume_error_rel = (volume - reference) / reference;
    return t;
  };
  q.tissues = {tissue("fat", 1000, 1010), tissue("skin", 39, 100), tissue("tumor", 106, 100)};
  q.tissues.push_back(TissueQuality{});  // no reference volume: never a warning
  q.tissues.back().name = "unknown";
  MeshChecks checks;  // 5 %
  const std::vector<VolumeDeviation> d = volume_deviations(q, checks);
  ASSERT_EQ(d.size(), 2u);
  EXPECT_EQ(d[0].tissue, "skin");
  EXPECT_NEAR(d[0].error_percent, -61.0, 1e-12);
  EXPECT_EQ(d[1].tissue, "tumor");
  const std::vector<std::string> w = volume_warnings(d, checks);
  ASSERT_EQ(w.size(), 2u);
  EXPECT_NE(w[0].find("tissue 'skin'"), std::string::npos) << w[0];
  EXPECT_NE(w[0].find("-61.0 %"), std::string::npos) << w[0];
  checks.volume_tolerance_percent = 7;
  EXPECT_EQ(volume_deviations(q, checks).size(), 1u);
}
