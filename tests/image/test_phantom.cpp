// Tests of the built-in breast phantom: determinism, tissue inventory, skin thickness, the air
// touching only skin, FGT islands as separate components, the oblique header, parameter errors.
// The default phantom (~3 million voxels) is generated once and shared by the tests.
#include "image/phantom.h"

#include "core/errors.h"
#include "core/yaml_map.h"
#include "support/tolerances.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <vector>

namespace tissuemesh {
namespace {

using Eigen::Vector3d;

constexpr double kPi = 3.14159265358979323846;

const LabelImage& default_phantom() {
  static const LabelImage image = make_breast_phantom(PhantomParams{});
  return image;
}

Vector3d center_of(const LabelImage& img, int i, int j, int k) {
  return img.to_physical(Vector3d(i, j, k));
}

// Label of the voxel whose box holds physical point x, or -1 outside the image.
int label_at(const LabelImage& img, const Eigen::Matrix3d& to_index, const Vector3d& x) {
  Vector3d ijk = to_index * (x - img.origin);
  int idx[3];
  for (int a = 0; a < 3; ++a) {
    idx[a] = static_cast<int>(std::lround(ijk[a]));
    if (idx[a] < 0 || idx[a] >= img.dims[a]) return -1;
  }
  return img.at(idx[0], idx[1], idx[2]);
}

// 6-connected components of the voxels with label `value`: component id per voxel (-1 for
// other labels) and the size of every component.
struct Components {
  std::vector<int> id;
  std::vector<std::size_t> size;
};

Components components_of(const LabelImage& img, std::int32_t value) {
  Components c;
  c.id.assign(img.voxel_count(), -1);
  const std::ptrdiff_t stride[3] = {1, img.dims[0],
                                    static_cast<std::ptrdiff_t>(img.dims[0]) * img.dims[1]};
  std::vector<std::size_t> stack;
  for (std::size_t seed = 0; seed < img.voxel_count(); ++seed) {
    if (img.labels[seed] != value || c.id[seed] >= 0) continue;
    const int comp = static_cast<int>(c.size.size());
    c.size.push_back(0);
    c.id[seed] = comp;
    stack.assign(1, seed);
    while (!stack.empty()) {
      const std::size_t v = stack.back();
      stack.pop_back();
      ++c.size[comp];
      const std::ptrdiff_t rest = static_cast<std::ptrdiff_t>(v);
      const int pos[3] = {static_cast<int>(rest % img.dims[0]),
                          static_cast<int>(rest / img.dims[0] % img.dims[1]),
                          static_cast<int>(rest / stride[2])};
      for (int a = 0; a < 3; ++a) {
        for (int step : {-1, 1}) {
          if (pos[a] + step < 0 || pos[a] + step >= img.dims[a]) continue;
          const std::size_t w = static_cast<std::size_t>(rest + step * stride[a]);
          if (img.labels[w] == value && c.id[w] < 0) {
            c.id[w] = comp;
            stack.push_back(w);
          }
        }
      }
    }
  }
  return c;
}

TEST(Phantom, SameParametersGiveTheSameImageBitForBit) {
  const LabelImage again = make_breast_phantom(PhantomParams{});
  const LabelImage& first = default_phantom();
  EXPECT_EQ(again.dims, first.dims);
  EXPECT_EQ(again.spacing, first.spacing);
  EXPECT_EQ(again.origin, first.origin);
  EXPECT_EQ(again.direction, first.direction);
  EXPECT_TRUE(again.labels == first.labels);
}

// The default image is pinned: every compiler, optimisation level and IEEE-754 platform must
// give exactly these labels (checked with GCC 12 and Clang 14 at -O2 and -O3 -march=native).
// If the phantom is changed on purpose, record the new fingerprint here.
TEST(Phantom, MatchesItsRecordedFingerprint) {
  std::uint64_t hash = 14695981039346656037ull;  // FNV-1a (64 bit) over the label values
  for (std::int32_t l : default_phantom().labels) {
    hash ^= static_cast<std::uint32_t>(l);
    hash *= 1099511628211ull;
  }
  EXPECT_EQ(hash, 0x2fdc057571faf11eull);
}

TEST(Phantom, DifferentSeedGivesDifferentLabelsOnTheSameGrid) {
  PhantomParams params;
  params.seed = 2;
  const LabelImage other = make_breast_phantom(params);
  const LabelImage& first = default_phantom();
  ASSERT_EQ(other.dims, first.dims);
  EXPECT_EQ(other.origin, first.origin);
  std::size_t differ = 0;
  for (std::size_t v = 0; v < other.labels.size(); ++v)
    differ += other.labels[v] != first.labels[v];
  EXPECT_GT(differ, 1000u) << "seed changes FGT, tumour and surface";
}

TEST(Phantom, HeaderIsAnObliqueProperRotationWithTheRequestedSpacing) {
  const LabelImage& img = default_phantom();
  EXPECT_EQ(img.spacing, Vector3d(0.7, 0.7, 1.5));
  EXPECT_TRUE((img.direction.transpose() * img.direction)
                  .isIdentity(test::kRelativeRoundoff));
  EXPECT_NEAR(img.direction.determinant(), 1.0, test::kRelativeRoundoff);
  EXPECT_FALSE(img.direction.isIdentity(0.1));
  // i Right, j Anterior, k Superior, rotated by 8 degrees about the superior axis.
  const double cos8 = std::cos(8.0 * kPi / 180.0);
  EXPECT_NEAR(img.direction.col(0).dot(Vector3d(-1, 0, 0)), cos8, test::kRelativeRoundoff);
  EXPECT_NEAR(img.direction.col(1).dot(Vector3d(0, -1, 0)), cos8, test::kRelativeRoundoff);
  EXPECT_EQ(img.direction.col(2), Vector3d(0, 0, 1));
  EXPECT_NO_THROW(img.validate("phantom"));
  // A few million voxels, as documented.
  EXPECT_GT(img.voxel_count(), 2000000u);
  EXPECT_LT(img.voxel_count(), 5000000u);
}

TEST(Phantom, HasEveryTissueInPlausibleAmounts) {
  const LabelImage& img = default_phantom();
  const PhantomParams params;
  const auto counts = img.label_counts();
  for (std::int32_t label = kAir; label <= kThorax; ++label)
    EXPECT_GT(counts.count(label) ? counts.at(label) : 0u, 0u) << "label " << label;
  EXPECT_EQ(counts.size(), 7u) << "no label outside PhantomLabel";

  // Breast = the protruding part, anterior to the chest skin (y < -10 mm, beyond the 8 mm of
  // chest fat): FGT fraction of its interior (fat, FGT, tumour).
  std::size_t interior = 0, gland = 0, tumor = 0;
  Vector3d tumor_sum = Vector3d::Zero();
  for (int k = 0; k < img.dims[2]; ++k)
    for (int j = 0; j < img.dims[1]; ++j)
      for (int i = 0; i < img.dims[0]; ++i) {
        const std::int32_t l = img.at(i, j, k);
        if (l != kFat && l != kFgt && l != kTumor) continue;
        const Vector3d x = center_of(img, i, j, k);
        if (l == kTumor) {
          ++tumor;
          tumor_sum += x;
        }
        if (x.y() < -10.0) {
          ++interior;
          gland += l == kFgt;
        }
      }
  const double fgt_fraction = static_cast<double>(gland) / interior;
  EXPECT_GE(fgt_fraction, 0.10);
  EXPECT_LE(fgt_fraction, 0.40);

  const double sphere = kPi / 6.0 * std::pow(params.tumor_diameter_mm, 3);
  EXPECT_NEAR(tumor * img.voxel_volume(), sphere, 0.25 * sphere);
  EXPECT_LT((tumor_sum / tumor - params.tumor_center_mm).norm(), 2.0);
}

TEST(Phantom, MuscleAndThoraxReachTheImageBorder) {
  const LabelImage& img = default_phantom();
  // Muscle touches both lateral faces (i = 0 and the last i), as in real data.
  bool muscle_first = false, muscle_last = false;
  for (int k = 0; k < img.dims[2]; ++k)
    for (int j = 0; j < img.dims[1]; ++j) {
      muscle_first |= img.at(0, j, k) == kMuscle;
      muscle_last |= img.at(img.dims[0] - 1, j, k) == kMuscle;
    }
  EXPECT_TRUE(muscle_first);
  EXPECT_TRUE(muscle_last);
  // The posterior face (j = 0: j runs anteriorly) is thorax everywhere.
  for (int k = 0; k < img.dims[2]; ++k)
    for (int i = 0; i < img.dims[0]; ++i) ASSERT_EQ(img.at(i, 0, k), kThorax);
}

TEST(Phantom, AirTouchesOnlySkinAndSkinLiesOnlyAlongAir) {
  const LabelImage& img = default_phantom();
  const double t = PhantomParams{}.skin_thickness_mm;
  std::size_t bad_contacts = 0, skin_far_from_air = 0;
  for (int k = 0; k < img.dims[2]; ++k)
    for (int j = 0; j < img.dims[1]; ++j)
      for (int i = 0; i < img.dims[0]; ++i) {
        const std::int32_t l = img.at(i, j, k);
        if (l == kAir) {
          // No 6-neighbour of air is body other than skin.
          const int n[6][3] = {{i - 1, j, k}, {i + 1, j, k}, {i, j - 1, k},
                               {i, j + 1, k}, {i, j, k - 1}, {i, j, k + 1}};
          for (const auto& m : n) {
            if (m[0] < 0 || m[1] < 0 || m[2] < 0 || m[0] >= img.dims[0] || m[1] >= img.dims[1] ||
                m[2] >= img.dims[2])
              continue;
            const std::int32_t o = img.at(m[0], m[1], m[2]);
            bad_contacts += o != kAir && o != kSkin;
          }
        } else if (l == kSkin) {
          // Every skin voxel's box lies closer than t to an air voxel's box: skin is never on
          // the image border's cut faces.
          bool near_air = false;
          const int reach[3] = {2 + static_cast<int>(t / img.spacing[0]),
                                2 + static_cast<int>(t / img.spacing[1]),
                                2 + static_cast<int>(t / img.spacing[2])};
          for (int dk = -reach[2]; dk <= reach[2] && !near_air; ++dk)
            for (int dj = -reach[1]; dj <= reach[1] && !near_air; ++dj)
              for (int di = -reach[0]; di <= reach[0] && !near_air; ++di) {
                const int q[3] = {i + di, j + dj, k + dk};
                if (q[0] < 0 || q[1] < 0 || q[2] < 0 || q[0] >= img.dims[0] ||
                    q[1] >= img.dims[1] || q[2] >= img.dims[2] || img.at(q[0], q[1], q[2]) != kAir)
                  continue;
                const int d[3] = {di, dj, dk};
                double gap2 = 0.0;
                for (int a = 0; a < 3; ++a) {
                  const double g = std::max(std::abs(d[a]) - 1, 0) * img.spacing[a];
                  gap2 += g * g;
                }
                near_air = gap2 < t * t;
              }
          skin_far_from_air += !near_air;
        }
      }
  EXPECT_EQ(bad_contacts, 0u);
  EXPECT_EQ(skin_far_from_air, 0u);
}

// Distance from `from` along `dir` over the first run of skin, up to the first voxel that is
// neither skin nor `before` (the label expected ahead of the skin); -1 if the ray leaves the
// image, meets another label first or never crosses skin. Exact to one `step`.
double skin_run(const LabelImage& img, const Eigen::Matrix3d& to_index, const Vector3d& from,
                const Vector3d& dir, std::int32_t before, double step) {
  double run_start = -1.0;
  for (double s = 0.0; s < 200.0; s += step) {
    const int l = label_at(img, to_index, from + s * dir);
    if (l == kSkin) {
      if (run_start < 0.0) run_start = s;
    } else if (run_start >= 0.0) {
      return s - run_start;
    } else if (l != before) {
      return -1.0;
    }
  }
  return -1.0;
}

// Rays from inside the breast outwards over the anterior hemisphere.
//  - Along any line into the body the first skin_thickness_mm are skin: skin is every body
//    voxel whose box is closer than t to an air voxel's box.
//  - Along the surface normal n the skin is at most t + 2 e(n), e(n) = sum_a |n . axis_a| h_a the
//    voxel extent along n: the voxelised air reaches e/2 past the true surface, the deepest
//    skin box t + e/2 further and its far side another e. With 1.5 mm slices a 45-degree
//    anterior-superior surface reaches ~2.7 t, so the 2.5 t bound is checked on the 90th
//    percentile, and the median is at most 2 t.
// The normal at the exit point is estimated from the body voxels within 5 mm of it (their
// centroid lies behind the surface).
TEST(Phantom, SkinIsAtLeastItsThicknessAndAtMostAVoxelExtentMore) {
  const LabelImage& img = default_phantom();
  const double t = PhantomParams{}.skin_thickness_mm;
  const Eigen::Matrix3d to_index = img.index_to_physical().inverse();
  const Vector3d start(0.0, -30.0, 0.0);
  const double step = 0.01;  // mm; runs are measured to one step
  const int rays = 400;
  std::vector<double> normal_runs;
  for (int r = 0; r < rays; ++r) {
    // Fibonacci sphere: evenly spread directions; keep the anterior ones.
    const double y = 1.0 - 2.0 * (r + 0.5) / rays;
    const double phi = r * kPi * (3.0 - std::sqrt(5.0));
    const Vector3d dir(std::sqrt(1.0 - y * y) * std::cos(phi), y,
                       std::sqrt(1.0 - y * y) * std::sin(phi));
    if (dir.y() > -0.2) continue;
    // Outwards: the run of skin just before the first air.
    double exit = 0.0;
    while (label_at(img, to_index, start + exit * dir) != kAir) exit += step;
    double inner = exit - step;
    while (label_at(img, to_index, start + inner * dir) == kSkin) inner -= step;
    EXPECT_GE(exit - inner - step, t - step) << "along direction " << dir.transpose();

    const Vector3d e = start + exit * dir;
    Vector3d body_sum = Vector3d::Zero();
    int body_count = 0;
    for (double dz = -5.0; dz <= 5.0; dz += 0.5)
      for (double dy = -5.0; dy <= 5.0; dy += 0.5)
        for (double dx = -5.0; dx <= 5.0; dx += 0.5) {
          const Vector3d d(dx, dy, dz);
          if (d.norm() <= 5.0 && label_at(img, to_index, e + d) > kAir) {
            body_sum += d;
            ++body_count;
          }
        }
    const Vector3d inward = (body_sum / body_count).normalized();
    double extent = 0.0;
    for (int a = 0; a < 3; ++a)
      extent += std::abs(inward.dot(img.direction.col(a))) * img.spacing[a];
    const double run = skin_run(img, to_index, e - 2.0 * inward, inward, kAir, step);
    ASSERT_GT(run, 0.0) << "normal at direction " << dir.transpose();
    EXPECT_GE(run, t - step) << "normal at direction " << dir.transpose();
    EXPECT_LE(run, t + 2.0 * extent + step) << "normal at direction " << dir.transpose();
    normal_runs.push_back(run);
  }
  ASSERT_GT(normal_runs.size(), 100u);
  std::sort(normal_runs.begin(), normal_runs.end());
  const double median = normal_runs[normal_runs.size() / 2];
  const double p90 = normal_runs[normal_runs.size() * 9 / 10];
  EXPECT_LE(median, 2.0 * t);
  EXPECT_LE(p90, 2.5 * t);
  RecordProperty("skin_normal_min_mm", std::to_string(normal_runs.front()));
  RecordProperty("skin_normal_median_mm", std::to_string(median));
  RecordProperty("skin_normal_p90_mm", std::to_string(p90));
  RecordProperty("skin_normal_max_mm", std::to_string(normal_runs.back()));
}

TEST(Phantom, FgtIslandsAreSeparateComponentsWellAwayFromEverythingElse) {
  const LabelImage& img = default_phantom();
  const PhantomParams params;
  PhantomParams without;
  without.fgt_islands = 0;
  const LabelImage bare = make_breast_phantom(without);
  ASSERT_EQ(bare.dims, img.dims);

  const Components with_islands = components_of(img, kFgt);
  const Components no_islands = components_of(bare, kFgt);
  const std::size_t main_size =
      *std::max_element(with_islands.size.begin(), with_islands.size.end());
  std::size_t fgt_total = 0;
  for (std::size_t s : with_islands.size) fgt_total += s;
  EXPECT_GT(main_size, fgt_total / 2) << "one main FGT tree";
  // The islands are exactly the new components: each one component, touching nothing else.
  EXPECT_EQ(with_islands.size.size(), no_islands.size.size() + params.fgt_islands);
  EXPECT_GE(with_islands.size.size(), 1u + params.fgt_islands);

  // Island voxels = FGT here, fat without islands; everything else identical.
  std::map<int, std::vector<std::size_t>> islands;
  for (std::size_t v = 0; v < img.voxel_count(); ++v) {
    if (img.labels[v] == bare.labels[v]) continue;
    ASSERT_EQ(img.labels[v], kFgt);
    ASSERT_EQ(bare.labels[v], kFat);
    islands[with_islands.id[v]].push_back(v);
  }
  ASSERT_EQ(islands.size(), static_cast<std::size_t>(params.fgt_islands));
  const double gap = 4.0 * img.spacing.maxCoeff();  // 3 whole voxels between centres
  for (const auto& [comp, voxels] : islands) {
    const double volume = voxels.size() * img.voxel_volume();
    EXPECT_GE(volume, 4.0 / 3.0 * kPi * std::pow(1.5 * 0.85, 3)) << "radius >= 1.5 mm";
    EXPECT_LE(volume, 4.0 / 3.0 * kPi * std::pow(4.0 * 1.15, 3)) << "radius <= 4 mm";
    EXPECT_EQ(with_islands.size[comp], voxels.size()) << "island is one whole component";
    // Nothing but fat (or the island itself) within the gap around every island voxel.
    for (std::size_t v : voxels) {
      const int i = static_cast<int>(v % img.dims[0]);
      const int j = static_cast<int>(v / img.dims[0] % img.dims[1]);
      const int k = static_cast<int>(v / (static_cast<std::size_t>(img.dims[0]) * img.dims[1]));
      const Vector3d x = center_of(img, i, j, k);
      const int reach[3] = {static_cast<int>(gap / img.spacing[0]),
                            static_cast<int>(gap / img.spacing[1]),
                            static_cast<int>(gap / img.spacing[2])};
      for (int dk = -reach[2]; dk <= reach[2]; ++dk)
        for (int dj = -reach[1]; dj <= reach[1]; ++dj)
          for (int di = -reach[0]; di <= reach[0]; ++di) {
            const int q[3] = {i + di, j + dj, k + dk};
            if (q[0] < 0 || q[1] < 0 || q[2] < 0 || q[0] >= img.dims[0] ||
                q[1] >= img.dims[1] || q[2] >= img.dims[2])
              continue;
            if ((center_of(img, q[0], q[1], q[2]) - x).norm() >= gap) continue;
            const std::size_t w = img.index(q[0], q[1], q[2]);
            ASSERT_TRUE(img.labels[w] == kFat || with_islands.id[w] == comp)
                << "label " << img.labels[w] << " within " << gap << " mm of an island";
          }
    }
  }
}

// --- parameters ---

YamlMap yaml(const std::string& text) { return YamlMap(YAML::Load(text), "", "phantom.yaml"); }

// Runs parse_phantom_params + finish on `text`; returns the InputError message ("" if none).
std::string parse_error(const std::string& text) {
  YamlMap map = yaml(text);
  try {
    parse_phantom_params(map);
    map.finish();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(PhantomParams, BadValuesAreInputErrorsNamingTheKey) {
  EXPECT_NE(parse_error("breast_width_mm: -10").find("breast_width_mm"), std::string::npos);
  EXPECT_NE(parse_error("breast_depth_mm: 0").find("breast_depth_mm"), std::string::npos);
  EXPECT_NE(parse_error("tumor_diameter_mm: -1").find("tumor_diameter_mm"), std::string::npos);
  EXPECT_NE(parse_error("tumor_center_mm: [0, -90, 0]").find("tumor_center_mm"),
            std::string::npos);
  EXPECT_NE(parse_error("tumor_center_mm: [80, -20, 0]").find("tumor_center_mm"),
            std::string::npos);
  EXPECT_NE(parse_error("tumor_center_mm: [0, 5, 0]").find("tumor_center_mm"),
            std::string::npos);
  EXPECT_NE(parse_error("spacing_mm: [0.7, 0.7]").find("spacing_mm"), std::string::npos);
  EXPECT_NE(parse_error("spacing_mm: [0.7, -0.7, 1.5]").find("spacing_mm"), std::string::npos);
  EXPECT_NE(parse_error("spacing_mm: [0.7, fine, 1.5]").find("spacing_mm"), std::string::npos);
  EXPECT_NE(parse_error("skin_thickness_mm: 0.2").find("skin_thickness_mm"), std::string::npos);
  EXPECT_NE(parse_error("oblique_deg: 60").find("oblique_deg"), std::string::npos);
  EXPECT_NE(parse_error("fgt_islands: -1").find("fgt_islands"), std::string::npos);
  EXPECT_NE(parse_error("seed: -3").find("seed"), std::string::npos);
  EXPECT_NE(parse_error("muscle_thickness_mm: big").find("muscle_thickness_mm"),
            std::string::npos);
  EXPECT_NE(parse_error("breast_widht_mm: 100").find("breast_widht_mm"), std::string::npos)
      << "unknown key";
  EXPECT_EQ(parse_error(""), "") << "every key is optional";

  PhantomParams bad;
  bad.tumor_center_mm = Vector3d(0.0, -100.0, 0.0);
  try {
    make_breast_phantom(bad);
    ADD_FAILURE() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("tumor_center_mm"), std::string::npos) << e.what();
  }
}

TEST(PhantomParams, PrintedConfigParsesBackToTheSameParameters) {
  PhantomParams p;
  p.seed = 7;
  p.spacing_mm = Vector3d(0.6, 0.65, 1.2);
  p.oblique_deg = -12.5;
  p.breast_width_mm = 120.0 / 3.0 * 3.1;  // not a short decimal: checks full precision
  p.breast_height_mm = 95.0;
  p.breast_depth_mm = 80.0;
  p.skin_thickness_mm = 2.0;
  p.muscle_thickness_mm = 10.0;
  p.tumor_center_mm = Vector3d(-5.0, -35.0, 4.0);
  p.tumor_diameter_mm = 12.0;
  p.fgt_islands = 3;
  YAML::Emitter out;
  phantom_params_to_yaml(p, out);
  ASSERT_TRUE(out.good()) << out.GetLastError();
  YamlMap map = yaml(out.c_str());
  const PhantomParams q = parse_phantom_params(map);
  EXPECT_NO_THROW(map.finish());
  EXPECT_EQ(q.seed, p.seed);
  EXPECT_EQ(q.spacing_mm, p.spacing_mm);
  EXPECT_EQ(q.oblique_deg, p.oblique_deg);
  EXPECT_EQ(q.breast_width_mm, p.breast_width_mm);
  EXPECT_EQ(q.breast_height_mm, p.breast_height_mm);
  EXPECT_EQ(q.breast_depth_mm, p.breast_depth_mm);
  EXPECT_EQ(q.skin_thickness_mm, p.skin_thickness_mm);
  EXPECT_EQ(q.muscle_thickness_mm, p.muscle_thickness_mm);
  EXPECT_EQ(q.tumor_center_mm, p.tumor_center_mm);
  EXPECT_EQ(q.tumor_diameter_mm, p.tumor_diameter_mm);
  EXPECT_EQ(q.fgt_islands, p.fgt_islands);
}

}  // namespace
}  // namespace tissuemesh
