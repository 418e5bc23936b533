// Tests of the phantom kinds behind one entry point: the breast kind is the built-in phantom bit
// for bit, no_background removes label 0 from every kind and adds a tiny tissue, the config keys
// (kind, no_background, the per-kind sections) parse, print and fail naming the key.
#include "image/make_phantom.h"

#include "core/errors.h"
#include "image/no_background.h"
#include "support/hard_image_checks.h"

#include <gtest/gtest.h>

#include <string>

namespace tissuemesh {
namespace {

using hard_label::kClip;
using hard_label::kPadding;

PhantomParams parse(const std::string& yaml) {
  YamlMap map(YAML::Load(yaml), "phantom", "test.yaml");
  PhantomParams p = parse_phantom_params(map);
  map.finish();
  return p;
}

std::string error_of(const std::string& yaml) {
  try {
    parse(yaml);
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

TEST(MakePhantom, BreastKindIsTheBuiltInPhantomUnchanged) {
  PhantomParams p;
  p.spacing_mm = {1.5, 1.5, 2.0};  // coarse: fast
  const LabelImage a = make_phantom(p), b = make_breast_phantom(p);
  EXPECT_TRUE(a.labels == b.labels);
  EXPECT_EQ(a.direction, b.direction);
}

TEST(MakePhantom, BreastWithoutBackgroundHasPaddingAndAClipAndNoZero) {
  PhantomParams p;
  p.spacing_mm = {1.5, 1.5, 2.0};
  const LabelImage with = make_breast_phantom(p);
  p.no_background = true;
  const LabelImage img = make_phantom(p);
  const auto counts = img.label_counts();
  EXPECT_EQ(counts.count(0), 0u);
  EXPECT_EQ(counts.at(kClip), 33u);
  EXPECT_EQ(counts.at(kPadding), with.label_counts().at(kAir));
  // Every face of the box holds tissue; the four sides hold several (interfaces run into
  // them); anterior is all padding, posterior all thorax.
  int mixed = 0;
  for (const auto& f : test::face_labels(img)) {
    EXPECT_EQ(f.count(0), 0u);
    mixed += f.size() >= 2;
  }
  EXPECT_EQ(mixed, 4);
}

TEST(MakePhantom, FragmentedBreastWithoutBackgroundTouchesEveryFaceWithSeveralTissues) {
  PhantomParams p;
  p.kind = "fragmented-breast";
  p.no_background = true;
  p.fragmented_breast.size_mm = {40.0, 40.0, 32.0};
  p.fragmented_breast.fgt_islands = 100;
  p.fragmented_breast.tumor_diameter_mm = 6.0;
  const LabelImage img = make_phantom(p);
  const auto counts = img.label_counts();
  EXPECT_EQ(counts.count(0), 0u);
  EXPECT_GT(counts.at(kPadding), 0u);
  EXPECT_EQ(counts.at(kClip), 33u);
  const auto faces = test::face_labels(img);
  EXPECT_EQ(faces[2], std::set<std::int32_t>{kPadding}) << "anterior face";
  EXPECT_TRUE(faces[3].count(kThorax)) << "posterior face";
  for (int face : {0, 1, 4, 5})
    for (std::int32_t l : std::initializer_list<std::int32_t>{kPadding, kSkin, kFat, kMuscle, kThorax})
      EXPECT_TRUE(faces[face].count(l)) << "face " << face << " label " << l;
  // No padding-free way round: padding touches only skin (the air did).
  for (const auto& [a, b] : test::touching_pairs(img))
    if (a == kPadding || b == kPadding) {
      EXPECT_EQ(a == kPadding ? b : a, kSkin);
    }
}

TEST(MakePhantom, FoldedLayersKindHonoursNoBackground) {
  PhantomParams p;
  p.kind = "folded-layers";
  p.no_background = true;
  p.folded_layers.size_mm = 80.0;
  p.folded_layers.deep_radius_mm = 5.0;
  const LabelImage img = make_phantom(p);
  EXPECT_EQ(img.label_counts().count(0), 0u);
}

TEST(MakePhantom, KeysParseAndPrintBack) {
  const PhantomParams p = parse(
      "{kind: fragmented-breast, no_background: true, fragmented_breast: {seed: 4, spacing_mm: 0.25, "
      "fgt_islands: 10}, folded_layers: {fold_period_mm: 2.5}}");
  EXPECT_EQ(p.kind, "fragmented-breast");
  EXPECT_TRUE(p.no_background);
  EXPECT_EQ(p.fragmented_breast.seed, 4u);
  EXPECT_EQ(p.fragmented_breast.spacing_mm, 0.25);
  EXPECT_EQ(p.fragmented_breast.fgt_islands, 10);
  EXPECT_EQ(p.folded_layers.fold_period_mm, 2.5);
  YAML::Emitter out;
  phantom_params_to_yaml(p, out);
  const PhantomParams back = parse(out.c_str());
  EXPECT_EQ(back.kind, p.kind);
  EXPECT_EQ(back.no_background, p.no_background);
  EXPECT_EQ(back.fragmented_breast.spacing_mm, p.fragmented_breast.spacing_mm);
  EXPECT_EQ(back.folded_layers.fold_period_mm, p.folded_layers.fold_period_mm);
}

TEST(MakePhantom, BadKeysAreInputErrorsNamingTheKey) {
  EXPECT_NE(error_of("{kind: brain}").find("phantom.kind"), std::string::npos);
  EXPECT_NE(error_of("{no_background: maybe}").find("phantom.no_background"), std::string::npos);
  EXPECT_NE(error_of("{fragmented_breast: {fgt_islands: -3}}").find("phantom.fragmented_breast.fgt_islands"),
            std::string::npos);
  EXPECT_NE(error_of("{fragmented_breast: {size_mm: [1, 2]}}").find("phantom.fragmented_breast.size_mm"),
            std::string::npos);
  EXPECT_NE(error_of("{folded_layers: {fold_period_mm: 1}}").find("phantom.folded_layers.fold_period_mm"),
            std::string::npos);
  EXPECT_NE(error_of("{folded_layers: {colour: red}}").find("colour"), std::string::npos);
}

}  // namespace
}  // namespace tissuemesh
