// Tests of the fragmented breast, measured on the generated images: grid and labels, thousands
// of separate FGT components, skin runs along axis rays, vessel radii, faces cut by the box,
// the clip, determinism, parameter errors. The default image (6.4 M voxels) is made once.
#include "image/fragmented_breast.h"

#include "core/errors.h"
#include "image/label_components.h"
#include "image/phantom.h"
#include "support/hard_image_checks.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <string>

namespace tissuemesh {
namespace {

using Eigen::Vector3d;
using hard_label::kClip;
using hard_label::kVessel;

const LabelImage& default_image() {
  static const LabelImage image = make_fragmented_breast(FragmentedBreastParams{});
  return image;
}

FragmentedBreastParams small_params() {
  FragmentedBreastParams p;
  p.size_mm = {40.0, 40.0, 32.0};  // 80 x 80 x 64 voxels
  p.fgt_islands = 150;
  p.fgt_diagonal_contacts = 50;
  p.tumor_diameter_mm = 6.0;
  return p;
}

std::size_t count_fgt_components(const LabelImage& img) {
  LabelImage fgt = img;
  for (std::int32_t& v : fgt.labels) v = v == kFgt ? 1 : 0;
  return find_components(fgt).components.size();
}

TEST(FragmentedBreast, DefaultGridIsIsotropicHalfMillimetreWithEveryLabel) {
  const LabelImage& img = default_image();
  EXPECT_EQ(img.dims, (std::array<int, 3>{200, 200, 160}));
  EXPECT_EQ(img.spacing, Vector3d::Constant(0.5));
  EXPECT_TRUE(img.direction.isIdentity());
  EXPECT_NO_THROW(img.validate("fragmented breast"));
  const auto counts = img.label_counts();
  std::vector<std::int32_t> labels;
  for (const auto& [label, n] : counts) labels.push_back(label);
  EXPECT_EQ(labels, (std::vector<std::int32_t>{0, 1, 2, 3, 4, 5, 6, 7, 8}));
  EXPECT_EQ(counts.at(kClip), 33u) << "the clip is a few tens of voxels";
  EXPECT_GT(counts.at(kVessel), 1000u);
}

TEST(FragmentedBreast, DefaultHasThousandsOfSeparateFgtComponents) {
  const std::size_t components = count_fgt_components(default_image());
  EXPECT_GE(components, 2000u);
  const FragmentedBreastParams p;
  EXPECT_GE(components, static_cast<std::size_t>(p.fgt_islands + p.fgt_diagonal_contacts) + 1);
}

TEST(FragmentedBreast, DiagonalContactsTouchFgtOnlyByAnEdgeOrACorner) {
  const LabelImage& img = default_image();
  LabelImage fgt = img;
  for (std::int32_t& v : fgt.labels) v = v == kFgt ? 1 : 0;
  const ComponentMap map = find_components(fgt);
  std::size_t contacts = 0;
  for (const LabelComponent& c : map.components) {
    if (c.voxels != 1) continue;
    const auto [i, j, k] = c.seed;
    bool diagonal = false;
    for (int dk = -1; dk <= 1; ++dk)
      for (int dj = -1; dj <= 1; ++dj)
        for (int di = -1; di <= 1; ++di) {
          if ((di != 0) + (dj != 0) + (dk != 0) < 2) continue;
          const int a = i + di, b = j + dj, e = k + dk;
          if (a >= 0 && b >= 0 && e >= 0 && a < img.dims[0] && b < img.dims[1] && e < img.dims[2])
            diagonal = diagonal || img.at(a, b, e) == kFgt;
        }
    contacts += diagonal;
  }
  EXPECT_GE(contacts, static_cast<std::size_t>(FragmentedBreastParams{}.fgt_diagonal_contacts));
}

TEST(FragmentedBreast, ComponentCountFollowsTheRequestedIslands) {
  for (int islands : {0, 100, 400}) {
    FragmentedBreastParams p = small_params();
    p.fgt_islands = islands;
    p.seed = 3;
    const LabelImage img = make_fragmented_breast(p);
    EXPECT_GE(count_fgt_components(img), static_cast<std::size_t>(islands + p.fgt_diagonal_contacts) + 1)
        << islands << " islands";
  }
}

TEST(FragmentedBreast, IslandsRangeFromOneVoxelToAFewMillimetres) {
  LabelImage fgt = default_image();
  for (std::int32_t& v : fgt.labels) v = v == kFgt ? 1 : 0;
  const ComponentMap map = find_components(fgt);
  std::size_t single = 0, largest_island = 0;
  for (const LabelComponent& c : map.components) {
    single += c.voxels == 1;
    std::array<int, 3> extent;
    for (int a = 0; a < 3; ++a) extent[a] = c.box_max[a] - c.box_min[a] + 1;
    // Islands: at most island_max_diameter_mm x 1.3 (stretch) across.
    if (*std::max_element(extent.begin(), extent.end()) * 0.5 <= 3.0 * 1.3 + 0.5)
      largest_island = std::max(largest_island, c.voxels);
  }
  EXPECT_GT(single, 100u) << "many one-voxel islands";
  EXPECT_GT(largest_island, 50u) << "some islands are millimetres across";
}

TEST(FragmentedBreast, SkinRunsAlongAxisRaysAreItsThicknessInVoxels) {
  for (double thickness : {1.0, 1.5, 2.0}) {
    FragmentedBreastParams p = small_params();
    p.skin_thickness_mm = thickness;
    const LabelImage img = make_fragmented_breast(p);
    const std::vector<int> runs = test::runs_after(img, kAir, kSkin);
    ASSERT_GT(runs.size(), 1000u);
    const int expected = static_cast<int>(std::floor(thickness / 0.5 + 1e-9));  // 2, 3, 4
    EXPECT_EQ(*std::min_element(runs.begin(), runs.end()), expected) << thickness << " mm";
    const auto square = std::count_if(runs.begin(), runs.end(), [&](int r) { return r <= expected + 1; });
    EXPECT_GT(square, static_cast<long>(runs.size() / 2)) << "oblique rays cross more skin, not most";
  }
}

TEST(FragmentedBreast, AirTouchesOnlySkin) {
  const auto pairs = test::touching_pairs(default_image());
  for (const auto& [a, b] : pairs)
    if (a == kAir) {
      EXPECT_EQ(b, kSkin) << "air touches label " << b;
    }
}

TEST(FragmentedBreast, VesselRadiiStayWithinTheRequestedRange) {
  const LabelImage& img = default_image();
  const FragmentedBreastParams p;
  const double r_max = 0.5 * p.vessel_max_diameter_mm, h = p.spacing_mm;
  std::vector<double> depth;  // distance of each vessel voxel to the nearest non-vessel voxel
  std::size_t one_voxel_thick = 0;
  for (int k = 0; k < img.dims[2]; ++k)
    for (int j = 0; j < img.dims[1]; ++j)
      for (int i = 0; i < img.dims[0]; ++i) {
        if (img.at(i, j, k) != kVessel) continue;
        depth.push_back(test::distance_to_other(img, i, j, k, kVessel, 6));
        int open = 0;  // non-vessel 6-neighbours
        open += i == 0 || img.at(i - 1, j, k) != kVessel;
        open += i + 1 == img.dims[0] || img.at(i + 1, j, k) != kVessel;
        open += j == 0 || img.at(i, j - 1, k) != kVessel;
        open += j + 1 == img.dims[1] || img.at(i, j + 1, k) != kVessel;
        open += k == 0 || img.at(i, j, k - 1) != kVessel;
        open += k + 1 == img.dims[2] || img.at(i, j, k + 1) != kVessel;
        one_voxel_thick += open >= 4;
      }
  ASSERT_FALSE(depth.empty());
  std::sort(depth.begin(), depth.end());
  // The trunks reach the largest radius: their axis voxels lie > r_max from any outside voxel.
  EXPECT_GE(depth.back(), r_max);
  // A voxel within r of a tube axis has an outside voxel within r + h (one more voxel along an
  // axis direction across the tube). Branch points and crossings widen a little: 99.5% bound.
  EXPECT_LE(depth[depth.size() * 995 / 1000], r_max + h);
  // The thinnest branches (0.5 mm, one voxel) are voxel chains.
  EXPECT_GT(one_voxel_thick, 200u);
}

TEST(FragmentedBreast, ChestTouchesFiveFacesAndTheBoxCutsTheBreast) {
  const LabelImage& img = default_image();
  const auto faces = test::face_labels(img);
  int muscle_faces = 0;
  for (const auto& f : faces) muscle_faces += f.count(kMuscle);
  EXPECT_GE(muscle_faces, 3);
  EXPECT_TRUE(faces[3].count(kThorax)) << "posterior face";
  EXPECT_FALSE(faces[2].count(kMuscle) || faces[2].count(kFat)) << "anterior face: air";
  // The superior and inferior faces cut the breast well in front of the chest: fat there,
  // anterior of the chest-wall fat (which ends 8 mm in front of the muscle at default size).
  for (int face_k : {0, img.dims[2] - 1}) {
    bool breast_cut = false;
    for (int j = 0; j < img.dims[1] && !breast_cut; ++j)
      for (int i = 0; i < img.dims[0] && !breast_cut; ++i)
        breast_cut = img.at(i, j, face_k) == kFat && img.to_physical(Vector3d(i, j, face_k)).y() < -20.0;
    EXPECT_TRUE(breast_cut) << "face k = " << face_k;
  }
}

TEST(FragmentedBreast, ClipTouchesOnlyFat) {
  for (const auto& [a, b] : test::touching_pairs(default_image()))
    if (a == kClip || b == kClip) {
      EXPECT_EQ(a == kClip ? b : a, kFat);
    }
}

TEST(FragmentedBreast, SameParametersGiveTheSameBytesAndSeedsDiffer) {
  const FragmentedBreastParams p = small_params();
  const LabelImage a = make_fragmented_breast(p), b = make_fragmented_breast(p);
  EXPECT_EQ(a.dims, b.dims);
  EXPECT_EQ(a.origin, b.origin);
  EXPECT_TRUE(a.labels == b.labels);
  FragmentedBreastParams q = p;
  q.seed = 2;
  EXPECT_FALSE(make_fragmented_breast(q).labels == a.labels);
}

TEST(FragmentedBreast, OutOfBoundsParametersAreInputErrorsNamingTheKey) {
  const std::vector<std::pair<std::string, std::function<void(FragmentedBreastParams&)>>> cases = {
      {"spacing_mm", [](auto& p) { p.spacing_mm = 0.05; }},
      {"spacing_mm", [](auto& p) { p.spacing_mm = NAN; }},
      {"size_mm", [](auto& p) { p.size_mm.y() = 10.0; }},
      {"size_mm", [](auto& p) { p.spacing_mm = 0.1; p.size_mm = {600, 600, 600}; }},
      {"skin_thickness_mm", [](auto& p) { p.skin_thickness_mm = 0.4; }},
      {"skin_thickness_mm", [](auto& p) { p.skin_thickness_mm = 6.0; }},
      {"vessel_max_diameter_mm", [](auto& p) { p.vessel_max_diameter_mm = 8.0; }},
      {"vessel_min_diameter_mm", [](auto& p) { p.vessel_min_diameter_mm = 3.0; }},
      {"fgt_islands", [](auto& p) { p.fgt_islands = -1; }},
      {"fgt_diagonal_contacts", [](auto& p) { p.fgt_diagonal_contacts = 100001; }},
      {"island_max_diameter_mm", [](auto& p) { p.island_max_diameter_mm = 11.0; }},
      {"tumor_diameter_mm", [](auto& p) { p.tumor_diameter_mm = 13.0; }},  // > 0.3 x 40 mm
      {"seed", [](auto& p) { p.seed = 2147483648u; }},
      {"fgt_islands", [](auto& p) { p.fgt_islands = 200000; }},  // do not fit in 40 mm
  };
  for (const auto& [key, change] : cases) {
    FragmentedBreastParams p = small_params();
    change(p);
    try {
      make_fragmented_breast(p);
      ADD_FAILURE() << key << ": no error";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("fragmented_breast." + key), std::string::npos) << e.what();
    }
  }
}

TEST(FragmentedBreast, PrintedParametersParseBackTheSame) {
  FragmentedBreastParams p = small_params();
  p.seed = 9;
  p.skin_thickness_mm = 1.25;
  YAML::Emitter out;
  fragmented_breast_params_to_yaml(p, out);
  YamlMap map(YAML::Load(out.c_str()), "phantom.fragmented_breast", "test");
  const FragmentedBreastParams back = parse_fragmented_breast_params(map);
  map.finish();
  EXPECT_EQ(back.seed, p.seed);
  EXPECT_EQ(back.size_mm, p.size_mm);
  EXPECT_EQ(back.skin_thickness_mm, p.skin_thickness_mm);
  EXPECT_EQ(back.fgt_islands, p.fgt_islands);
  EXPECT_EQ(back.tumor_diameter_mm, p.tumor_diameter_mm);
}

}  // namespace
}  // namespace tissuemesh
