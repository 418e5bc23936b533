// Folded layers; folded_layers.h describes the geometry and the contract.
//
// The fold field is a sum of one sine per axis, so it is tabulated per axis (three short tables)
// and the pass over the voxels costs one square root each. Nesting at the voxel level: for two
// 6-neighbours p, q (centres h apart) r changes by at most h and g by at most h |grad g|max =
// h 2 pi / (P sqrt 3); a layer between interfaces r = Ro + Ao g and r = Ri + Ai g cannot be
// skipped when Ro - Ri >= h + (Ao == Ai ? Ao h |grad g|max : Ao + Ai). check_ enforces that.
#ifdef __clang__
#pragma STDC FP_CONTRACT OFF
#endif

#include "image/folded_layers.h"
#include "image/param_bounds.h"

#include "core/errors.h"
#include "image/no_background.h"
#include "image/phantom_random.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <sstream>
#include <vector>

namespace tissuemesh {
namespace {

using phantom_random::kPi;
constexpr double kMaxVoxels = 60e6;
constexpr int kLesionRoomVoxels = 8;  // white matter this thick (voxels) holds the lesion's ball

struct Radii {
  double r[6];  // r[0] outer, r[1] scalp/skull, r[2] skull/CSF, r[3] CSF/grey mean,
                // r[4] grey/white mean, r[5] white/deep
};

int grid_size(const FoldedLayersParams& p) {
  return std::max(1, static_cast<int>(std::lround(p.size_mm / p.spacing_mm)));
}

Radii radii(const FoldedLayersParams& p, bool no_background) {
  Radii R;
  const double half = 0.5 * (grid_size(p) - 1) * p.spacing_mm;  // centre to the outer voxel centres
  R.r[0] = no_background ? half * std::sqrt(3.0) + p.spacing_mm : 0.45 * p.size_mm;
  for (int l = 0; l < 4; ++l) R.r[l + 1] = R.r[l] - p.layer_thickness_mm[l];
  R.r[5] = p.deep_radius_mm;
  return R;
}

}  // namespace

void check_folded_layers_params(const FoldedLayersParams& p, bool no_background,
                                const std::function<std::string(const char*)>& where) {
  const ParamBounds bounds(where);
  auto fail = [&](const char* key, const std::string& rule) { bounds.fail(key, rule); };
  auto range = [&](const char* key, double v, double lo, double hi) { bounds.range(key, v, lo, hi); };
  if (p.seed > 2147483647u) fail("seed", "must be an integer in [0, 2147483647]");
  range("spacing_mm", p.spacing_mm, 0.1, 5.0);
  range("size_mm", p.size_mm, 10.0, 1000.0);
  const double n = grid_size(p);
  if (n * n * n > kMaxVoxels) fail("size_mm", "size_mm / spacing_mm gives more than 60 million voxels");
  range("fold_period_mm", p.fold_period_mm, 2.0 * p.spacing_mm, 100.0);
  range("fold_amplitude_mm", p.fold_amplitude_mm, 0.0, 20.0);
  const double h = p.spacing_mm, A = p.fold_amplitude_mm;
  const double fold_step = A * h * 2.0 * kPi / (p.fold_period_mm * std::sqrt(3.0));
  // Least radial thickness of scalp, skull, CSF and grey (see the file comment).
  const double least[4] = {h, h, h + A, h + fold_step};
  for (int l = 0; l < 4; ++l)
    if (!(p.layer_thickness_mm[l] >= least[l])) {
      std::ostringstream msg;
      msg << "layer " << l + 1 << " of 4 (scalp, skull, csf, grey) is " << p.layer_thickness_mm[l]
          << " mm; with spacing " << h << " mm and fold amplitude " << A << " mm it needs >= " << least[l]
          << " mm so that neighbouring voxels never skip it";
      fail("layer_thickness_mm", msg.str());
    }
  range("deep_radius_mm", p.deep_radius_mm, 2.0 * h, 1000.0);
  const Radii R = radii(p, no_background);
  const double white = R.r[4] - A - R.r[5];  // least radial thickness of the white matter
  if (!(white >= kLesionRoomVoxels * h)) {
    std::ostringstream msg;
    msg << "leaves " << white << " mm of white matter (at most; " << kLesionRoomVoxels * h
        << " mm needed for the lesion): make it smaller, the layers thinner or size_mm larger";
    fail("deep_radius_mm", msg.str());
  }
}

FoldedLayersParams parse_folded_layers_params(YamlMap& map) {
  FoldedLayersParams p;
  p.seed = static_cast<std::uint32_t>(map.integer("seed", static_cast<int>(p.seed)));
  p.spacing_mm = map.number("spacing_mm", p.spacing_mm);
  p.size_mm = map.number("size_mm", p.size_mm);
  p.fold_period_mm = map.number("fold_period_mm", p.fold_period_mm);
  p.fold_amplitude_mm = map.number("fold_amplitude_mm", p.fold_amplitude_mm);
  const YAML::Node t = map.raw("layer_thickness_mm");
  if (t.IsDefined() && !t.IsNull()) {
    bool ok = t.IsSequence() && t.size() == 4;
    for (std::size_t l = 0; ok && l < 4; ++l)
      ok = YAML::convert<double>::decode(t[l], p.layer_thickness_mm[l]) && std::isfinite(p.layer_thickness_mm[l]);
    if (!ok)
      throw InputError(map.where("layer_thickness_mm") + ": expected a list of 4 numbers (scalp, skull, csf, grey), got " +
                       YAML::Dump(t));
  }
  p.deep_radius_mm = map.number("deep_radius_mm", p.deep_radius_mm);
  // Checked for the background case here; make_folded_layers checks again for no_background.
  check_folded_layers_params(p, false, [&](const char* key) { return map.where(key); });
  return p;
}

void folded_layers_params_to_yaml(const FoldedLayersParams& p, YAML::Emitter& out) {
  out << YAML::BeginMap << YAML::Key << "seed" << YAML::Value << p.seed;
  out << YAML::Key << "spacing_mm" << YAML::Value << p.spacing_mm;
  out << YAML::Key << "size_mm" << YAML::Value << p.size_mm;
  out << YAML::Key << "fold_period_mm" << YAML::Value << p.fold_period_mm;
  out << YAML::Key << "fold_amplitude_mm" << YAML::Value << p.fold_amplitude_mm;
  out << YAML::Key << "layer_thickness_mm" << YAML::Value << YAML::Flow << YAML::BeginSeq;
  for (int l = 0; l < 4; ++l) out << p.layer_thickness_mm[l];
  out << YAML::EndSeq << YAML::Key << "deep_radius_mm" << YAML::Value << p.deep_radius_mm << YAML::EndMap;
}

LabelImage make_folded_layers(const FoldedLayersParams& p, bool no_background) {
  check_folded_layers_params(p, no_background, [](const char* key) {
    return std::string("phantom parameter folded_layers.") + key;
  });
  using namespace layer_label;
  const int n = grid_size(p);
  const double h = p.spacing_mm, A = p.fold_amplitude_mm;
  LabelImage img;
  img.dims = {n, n, n};
  img.spacing = Eigen::Vector3d::Constant(h);
  img.origin = Eigen::Vector3d::Constant(-0.5 * (n - 1) * h);
  img.labels.assign(img.voxel_count(), 0);

  phantom_random::Rng rng(p.seed);
  std::array<std::vector<double>, 3> wave;  // per axis: A/3 sin(2 pi x / P + phase)
  for (int a = 0; a < 3; ++a) {
    const double phase = rng.uniform(0.0, 2.0 * kPi);
    wave[a].resize(n);
    for (int q = 0; q < n; ++q)
      wave[a][q] = A / 3.0 * phantom_random::sine(2.0 * kPi * (img.origin[a] + q * h) / p.fold_period_mm + phase);
  }
  const Radii R = radii(p, no_background);
  std::size_t idx = 0;
  for (int k = 0; k < n; ++k) {
    const double z = img.origin.z() + k * h;
    for (int j = 0; j < n; ++j) {
      const double y = img.origin.y() + j * h;
      for (int i = 0; i < n; ++i, ++idx) {
        const double x = img.origin.x() + i * h;
        const double r = std::sqrt(x * x + y * y + z * z);
        const double fold = wave[0][i] + wave[1][j] + wave[2][k];
        std::int32_t label;
        if (r >= R.r[0]) label = 0;
        else if (r >= R.r[1]) label = kScalp;
        else if (r >= R.r[2]) label = kSkull;
        else if (r >= R.r[3] + fold) label = kCsf;
        else if (r >= R.r[4] + fold) label = kGrey;
        else if (r >= R.r[5]) label = kWhite;
        else label = kDeep;
        img.labels[idx] = label;
      }
    }
  }
  add_tiny_tissue(img, kWhite, kLesion, p.seed + 7);
  return img;
}

}  // namespace tissuemesh
