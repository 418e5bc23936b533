// Tests of the folded layers, measured on the generated images: grid and labels, nesting (each
// tissue touches only its neighbours), the fold period along lines, the variant without
// background (tissues cut by all six faces), determinism, parameter errors.
#include "image/folded_layers.h"

#include "core/errors.h"
#include "support/hard_image_checks.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <string>

namespace tissuemesh {
namespace {

using namespace layer_label;

const LabelImage& default_image() {
  static const LabelImage image = make_folded_layers(FoldedLayersParams{});
  return image;
}

// Every pair of touching labels differs by one, except the lesion, which touches white only.
void expect_nested(const LabelImage& img) {
  for (const auto& [a, b] : test::touching_pairs(img)) {
    if (a == kLesion || b == kLesion)
      EXPECT_EQ(a == kLesion ? b : a, kWhite) << "lesion touches " << (a == kLesion ? b : a);
    else
      EXPECT_EQ(b - a, 1) << "label " << a << " touches label " << b;
  }
}

// Most changes between "inside the CSF/grey interface" (label >= grey) and outside along one
// line parallel to x within |x| <= half_window_mm, over all lines.
int most_fold_crossings(const LabelImage& img, double half_window_mm) {
  int most = 0;
  const int n = img.dims[0], centre = n / 2;
  const int w = static_cast<int>(half_window_mm / img.spacing[0]);
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j) {
      int changes = 0;
      for (int i = centre - w + 1; i <= centre + w; ++i)
        changes += (img.at(i - 1, j, k) >= kGrey) != (img.at(i, j, k) >= kGrey);
      most = std::max(most, changes);
    }
  return most;
}

TEST(FoldedLayers, DefaultGridHoldsSixNestedTissuesAndTheLesion) {
  const LabelImage& img = default_image();
  EXPECT_EQ(img.dims, (std::array<int, 3>{120, 120, 120}));
  EXPECT_EQ(img.spacing, Eigen::Vector3d::Constant(1.0));
  const auto counts = img.label_counts();
  ASSERT_EQ(counts.size(), 8u);  // air, six layers, lesion
  for (std::int32_t l = 0; l <= kLesion; ++l) EXPECT_GT(counts.count(l), 0u) << l;
  EXPECT_EQ(counts.at(kLesion), 33u);
  expect_nested(img);
  const auto faces = test::face_labels(img);
  for (const auto& f : faces) EXPECT_EQ(f, std::set<std::int32_t>{0}) << "air all round";
}

TEST(FoldedLayers, GreyIsAFoldedSheetAFewVoxelsThick) {
  const LabelImage& img = default_image();
  // Axis rays from CSF through grey into white: a few voxels, about the radial thickness (4)
  // over the cosine of the angle at which an axis ray meets the sphere (up to ~2 for most).
  std::vector<int> runs = test::runs_after(img, kCsf, kGrey);
  ASSERT_GT(runs.size(), 1000u);
  std::sort(runs.begin(), runs.end());
  EXPECT_GE(runs.front(), 1);
  EXPECT_LE(runs[runs.size() / 2], 8);
}

TEST(FoldedLayers, FoldsRepeatWithTheRequestedPeriod) {
  // Half-millimetre voxels: 8 per period of 4 mm, 12 per 6 mm. Along a line at the right depth
  // the CSF/grey interface is crossed twice per period; a 12 mm window holds 3 or 2 periods.
  for (double period : {4.0, 6.0}) {
    FoldedLayersParams p;
    p.spacing_mm = 0.5;
    p.size_mm = 100.0;
    p.fold_period_mm = period;
    p.fold_amplitude_mm = 3.0;
    const LabelImage img = make_folded_layers(p);
    expect_nested(img);
    const double window = 12.0;
    const int expected = static_cast<int>(2.0 * window / period);
    const int most = most_fold_crossings(img, 0.5 * window);
    EXPECT_GE(most, expected - 1) << "period " << period;
    EXPECT_LE(most, expected + 2) << "period " << period;
  }
}

TEST(FoldedLayers, WithoutBackgroundFiveTissuesTouchAllSixFaces) {
  const LabelImage img = make_folded_layers(FoldedLayersParams{}, true);
  const auto counts = img.label_counts();
  EXPECT_EQ(counts.count(0), 0u) << "no background voxel";
  EXPECT_EQ(counts.at(kLesion), 33u);
  EXPECT_GT(counts.count(kDeep), 0u);
  for (const auto& f : test::face_labels(img))
    EXPECT_EQ(f, (std::set<std::int32_t>{kScalp, kSkull, kCsf, kGrey, kWhite}));
  expect_nested(img);
}

TEST(FoldedLayers, SameParametersGiveTheSameBytesAndSeedsDiffer) {
  FoldedLayersParams p;
  p.size_mm = 80.0;
  p.deep_radius_mm = 5.0;
  const LabelImage a = make_folded_layers(p), b = make_folded_layers(p);
  EXPECT_TRUE(a.labels == b.labels);
  EXPECT_EQ(a.origin, b.origin);
  p.seed = 2;
  EXPECT_FALSE(make_folded_layers(p).labels == a.labels);
}

TEST(FoldedLayers, OutOfBoundsParametersAreInputErrorsNamingTheKey) {
  const std::vector<std::pair<std::string, std::function<void(FoldedLayersParams&)>>> cases = {
      {"spacing_mm", [](auto& p) { p.spacing_mm = 0.01; }},
      {"size_mm", [](auto& p) { p.size_mm = 5.0; }},
      {"size_mm", [](auto& p) { p.spacing_mm = 0.1; p.size_mm = 1000.0; }},
      {"fold_period_mm", [](auto& p) { p.fold_period_mm = 1.5; }},   // < 2 voxels
      {"fold_amplitude_mm", [](auto& p) { p.fold_amplitude_mm = -1.0; }},
      {"layer_thickness_mm", [](auto& p) { p.layer_thickness_mm[3] = 2.0; }},  // grey skipped
      {"layer_thickness_mm", [](auto& p) { p.layer_thickness_mm[2] = 2.0; }},  // csf < h + A
      {"layer_thickness_mm", [](auto& p) { p.layer_thickness_mm[0] = 0.5; }},
      {"deep_radius_mm", [](auto& p) { p.deep_radius_mm = 30.0; }},  // no room for white
      {"deep_radius_mm", [](auto& p) { p.deep_radius_mm = 1.0; }},
      {"seed", [](auto& p) { p.seed = 4000000000u; }},
  };
  for (const auto& [key, change] : cases) {
    FoldedLayersParams p;
    change(p);
    try {
      make_folded_layers(p);
      ADD_FAILURE() << key << ": no error";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("folded_layers." + key), std::string::npos) << e.what();
    }
  }
}

TEST(FoldedLayers, PrintedParametersParseBackTheSame) {
  FoldedLayersParams p;
  p.seed = 5;
  p.fold_period_mm = 2.5;
  p.layer_thickness_mm = {3.0, 4.0, 5.0, 4.5};
  YAML::Emitter out;
  folded_layers_params_to_yaml(p, out);
  YamlMap map(YAML::Load(out.c_str()), "phantom.folded_layers", "test");
  const FoldedLayersParams back = parse_folded_layers_params(map);
  map.finish();
  EXPECT_EQ(back.seed, p.seed);
  EXPECT_EQ(back.fold_period_mm, p.fold_period_mm);
  EXPECT_EQ(back.layer_thickness_mm, p.layer_thickness_mm);
  EXPECT_EQ(back.size_mm, p.size_mm);
}

}  // namespace
}  // namespace tissuemesh
