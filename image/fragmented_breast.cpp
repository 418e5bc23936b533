// Fragmented breast; fragmented_breast.h describes the geometry and the contract.
//
// Order of the passes, and why: one pass over all voxels labels thorax, muscle, body and the
// main FGT (noise is evaluated only near the breast surface and inside the FGT envelope, so a
// 32 M voxel image stays fast); the tumour and the vessel tree are painted over their bounding
// boxes; skin is stamped from the air voxels next to the body (work ~ surface, no full-size
// distance buffer); the clip, the islands and the diagonal contacts come last, because an
// island is placed only where a box around it is all fat and a contact only where its six face
// neighbours are: nothing painted later touches either by a face, so each stays a component.
#ifdef __clang__
#pragma STDC FP_CONTRACT OFF
#endif

#include "image/fragmented_breast.h"
#include "image/param_bounds.h"

#include "core/errors.h"
#include "image/no_background.h"
#include "image/phantom.h"
#include "image/phantom_random.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <sstream>
#include <vector>

namespace tissuemesh {
namespace {

using Eigen::Vector3d;
using phantom_random::Rng;

constexpr double kMaxVoxels = 60e6;
constexpr double kAnteriorFraction = 0.7;  // field of view anterior of the chest wall, of size.y
constexpr double kMuscleFraction = 0.1;    // muscle thickness, of size.y
constexpr double kChestFatFraction = 0.08; // subcutaneous fat over the chest, of size.y
constexpr double kBreastIrregularity = 0.05;

struct Geometry {
  double h;
  Vector3d size;
  double a, c, d;           // breast semi-axes: L-R, S-I, anterior depth
  double muscle, chest_fat;  // mm
  double radius_lr, radius_si;
  std::uint32_t seed;

  explicit Geometry(const FragmentedBreastParams& p)
      : h(p.spacing_mm),
        size(p.size_mm),
        a(0.42 * p.size_mm.x()),
        c(0.75 * p.size_mm.z()),  // > half the box: the superior and inferior faces cut it
        d(0.62 * p.size_mm.y()),
        muscle(kMuscleFraction * p.size_mm.y()),
        chest_fat(kChestFatFraction * p.size_mm.y()),
        radius_lr(2.5 * p.size_mm.x()),
        radius_si(6.0 * p.size_mm.z()),
        seed(p.seed) {}

  // Anterior muscle surface y = kappa(x, z): through the origin, curving posteriorly.
  double kappa(double x, double z) const {
    return x * x / (2.0 * radius_lr) + z * z / (2.0 * radius_si);
  }
  // Breast: tapered half-ellipsoid, radius modulated by +-5% lattice noise (15 mm cells).
  bool in_breast(const Vector3d& p) const {
    if (p.y() > 0.0) return false;
    const double taper = 1.0 - 0.12 * std::min(-p.y() / d, 1.0);
    const double u = p.x() / (a * taper), v = p.y() / d, w = p.z() / (c * taper);
    const double rho2 = u * u + v * v + w * w;
    if (rho2 > 1.1 * 1.1) return false;
    if (rho2 < 0.94 * 0.94) return true;
    return std::sqrt(rho2) < 1.0 + kBreastIrregularity * phantom_random::lattice_noise(p, 15.0, seed);
  }
  // Main FGT: inside an ellipsoidal envelope, noise above a threshold that rises outwards:
  // dense lobular tissue in the middle, fragments towards the fat.
  bool in_main_fgt(const Vector3d& p) const {
    const double u = p.x() / (0.75 * a), v = (p.y() + 0.4 * d) / (0.45 * d), w = p.z() / (0.75 * c);
    const double q = u * u + v * v + w * w;
    if (q >= 1.0) return false;
    const double n = phantom_random::lattice_noise(p, 6.0, seed + 1) +
                     0.5 * phantom_random::lattice_noise(p, 2.5, seed + 2);
    return n > -0.1 + 0.7 * q;
  }
  Vector3d tumor_center() const { return {0.1 * a, -0.45 * d, 0.1 * c}; }
};

LabelImage make_grid(const FragmentedBreastParams& p) {
  LabelImage g;
  g.spacing = Vector3d::Constant(p.spacing_mm);
  const Vector3d lo(-0.5 * p.size_mm.x(), -kAnteriorFraction * p.size_mm.y(), -0.5 * p.size_mm.z());
  for (int a = 0; a < 3; ++a)
    g.dims[a] = std::max(1, static_cast<int>(std::lround(p.size_mm[a] / p.spacing_mm)));
  g.origin = lo + Vector3d::Constant(0.5 * p.spacing_mm);
  return g;
}

// Thorax, muscle, air, fat and the main FGT, one pass.
void label_body(LabelImage& img, const Geometry& g) {
  std::size_t idx = 0;
  for (int k = 0; k < img.dims[2]; ++k)
    for (int j = 0; j < img.dims[1]; ++j)
      for (int i = 0; i < img.dims[0]; ++i, ++idx) {
        const Vector3d x = img.origin + g.h * Vector3d(i, j, k);
        const double behind_wall = x.y() - g.kappa(x.x(), x.z());
        std::int32_t label;
        if (behind_wall >= g.muscle)
          label = kThorax;
        else if (behind_wall >= 0.0)
          label = kMuscle;
        else if (behind_wall < -g.chest_fat && !g.in_breast(x))
          label = kAir;
        else
          label = g.in_main_fgt(x) ? kFgt : kFat;
        img.labels[idx] = label;
      }
}

// Calls fn(index, physical centre) for every voxel whose centre is in the box [lo, hi].
template <class Fn>
void for_box(const LabelImage& img, const Vector3d& lo, const Vector3d& hi, Fn&& fn) {
  std::array<int, 3> first, last;
  for (int a = 0; a < 3; ++a) {
    const double h = img.spacing[a];
    first[a] = std::max(0, static_cast<int>(std::ceil((lo[a] - img.origin[a]) / h)));
    last[a] = std::min(img.dims[a] - 1, static_cast<int>(std::floor((hi[a] - img.origin[a]) / h)));
  }
  for (int k = first[2]; k <= last[2]; ++k)
    for (int j = first[1]; j <= last[1]; ++j)
      for (int i = first[0]; i <= last[0]; ++i)
        fn(img.index(i, j, k), Vector3d(img.origin + img.spacing.cwiseProduct(Vector3d(i, j, k))));
}

void add_tumor(LabelImage& img, const Geometry& g, double diameter) {
  const Vector3d c = g.tumor_center();
  const double r = 0.5 * diameter, reach = 1.25 * r;
  for_box(img, c - Vector3d::Constant(reach), c + Vector3d::Constant(reach),
          [&](std::size_t idx, const Vector3d& x) {
            std::int32_t& v = img.labels[idx];
            if (v != kFat && v != kFgt) return;
            // Lobulated: the radius varies by +-20% over cells of half the radius.
            const double lobes = phantom_random::lattice_noise(x, 0.5 * r, g.seed + 3);
            if ((x - c).norm() < r * (1.0 + 0.2 * lobes)) v = kTumor;
          });
}

struct Tube {
  Vector3d a, b;
  double r;
};

// Vessel tree: trunks leave the muscle anteriorly and branch in two (radius x0.82 and x0.7)
// until the thinnest radius; each branch is three pieces with random turns (tortuous). A
// branch that leaves the body or the box ends there.
std::vector<Tube> vessel_tree(const LabelImage& img, const Geometry& g, double r_max, double r_min,
                              Rng& rng) {
  std::vector<Tube> tubes;
  const Vector3d box_lo = img.origin, box_hi = img.origin + g.h * Vector3d(img.dims[0] - 1,
                                                                          img.dims[1] - 1, img.dims[2] - 1);
  auto inside_body = [&](const Vector3d& x) {
    if ((x.array() < box_lo.array()).any() || (x.array() > box_hi.array()).any()) return false;
    const double behind_wall = x.y() - g.kappa(x.x(), x.z());
    return behind_wall < g.muscle && (behind_wall >= -g.chest_fat || g.in_breast(x));
  };
  struct Branch {
    Vector3d p, dir;
    double r;
  };
  std::vector<Branch> todo;
  constexpr int kTrunks = 4;
  for (int t = 0; t < kTrunks; ++t) {
    const double x = g.a * rng.uniform(-0.5, 0.5);
    const double z = 0.5 * g.size.z() * rng.uniform(-0.6, 0.6);
    const Vector3d jitter = rng.unit_vector();
    todo.push_back({{x, g.kappa(x, z) + 0.5 * g.muscle, z},
                    (Vector3d(0.0, -1.0, 0.0) + 0.35 * jitter).normalized(), r_max});
  }
  constexpr std::size_t kMaxTubes = 60000;  // bound on the work, far above a default tree
  while (!todo.empty() && tubes.size() < kMaxTubes) {
    Branch b = todo.back();
    todo.pop_back();
    const double piece = (6.0 + 9.0 * b.r) / 3.0;
    bool alive = true;
    for (int s = 0; s < 3 && alive; ++s) {
      const Vector3d turn = rng.unit_vector();
      b.dir = (b.dir + 0.3 * turn).normalized();
      const Vector3d end = b.p + piece * b.dir;
      tubes.push_back({b.p, end, b.r});
      alive = inside_body(end);
      b.p = end;
    }
    const Vector3d side = rng.unit_vector();
    if (!alive || b.r <= r_min * (1.0 + 1e-9)) continue;
    Vector3d u = side - side.dot(b.dir) * b.dir;
    u = u.norm() > 1e-6 ? u.normalized() : b.dir.unitOrthogonal();
    if (0.82 * b.r < r_min) {  // one last piece at the thinnest radius
      todo.push_back({b.p, b.dir, r_min});
      continue;
    }
    todo.push_back({b.p, (b.dir + 0.5 * u).normalized(), 0.82 * b.r});
    todo.push_back({b.p, (b.dir - 0.6 * u).normalized(), std::max(r_min, 0.7 * b.r)});
  }
  return tubes;
}

// Vessels replace fat, FGT and muscle (not skin, tumour or thorax). A tube is painted at least
// sqrt(3)/2 voxels wide, which holds every voxel its axis passes through: a thin branch is a
// 6-connected chain of voxels, not a dotted line.
void paint_tubes(LabelImage& img, const std::vector<Tube>& tubes) {
  const double least = 0.5 * std::sqrt(3.0) * img.spacing[0];
  for (Tube t : tubes) {
    t.r = std::max(t.r, least);
    const Vector3d pad = Vector3d::Constant(t.r);
    const Vector3d ab = t.b - t.a;
    const double len2 = ab.squaredNorm();
    for_box(img, t.a.cwiseMin(t.b) - pad, t.a.cwiseMax(t.b) + pad,
            [&](std::size_t idx, const Vector3d& x) {
              std::int32_t& v = img.labels[idx];
              if (v != kFat && v != kFgt && v != kMuscle) return;
              const double s = len2 > 0.0 ? std::clamp((x - t.a).dot(ab) / len2, 0.0, 1.0) : 0.0;
              if ((x - t.a - s * ab).squaredNorm() <= t.r * t.r) v = hard_label::kVessel;
            });
  }
}

// Skin: every body voxel whose centre lies within `thickness` of an air voxel's centre. The
// air voxels next to the body are collected first (stamping never creates air), then a ball of
// index offsets is stamped around each. Image border faces are not air: no skin there.
void add_skin(LabelImage& img, double thickness) {
  const std::array<int, 3> n = img.dims;
  const double reach = thickness / img.spacing[0];
  const int r = static_cast<int>(std::floor(reach + 1e-9));
  std::vector<std::array<int, 3>> ball;
  for (int k = -r; k <= r; ++k)
    for (int j = -r; j <= r; ++j)
      for (int i = -r; i <= r; ++i)
        if ((i || j || k) && i * i + j * j + k * k <= reach * reach * (1.0 + 1e-12))
          ball.push_back({i, j, k});
  std::vector<std::array<int, 3>> surface_air;
  for (int k = 0; k < n[2]; ++k)
    for (int j = 0; j < n[1]; ++j)
      for (int i = 0; i < n[0]; ++i) {
        if (img.at(i, j, k) != kAir) continue;
        const bool next_to_body = (i > 0 && img.at(i - 1, j, k) != kAir) ||
                                  (i + 1 < n[0] && img.at(i + 1, j, k) != kAir) ||
                                  (j > 0 && img.at(i, j - 1, k) != kAir) ||
                                  (j + 1 < n[1] && img.at(i, j + 1, k) != kAir) ||
                                  (k > 0 && img.at(i, j, k - 1) != kAir) ||
                                  (k + 1 < n[2] && img.at(i, j, k + 1) != kAir);
        if (next_to_body) surface_air.push_back({i, j, k});
      }
  for (const auto& s : surface_air)
    for (const auto& o : ball) {
      const int i = s[0] + o[0], j = s[1] + o[1], k = s[2] + o[2];
      if (i < 0 || j < 0 || k < 0 || i >= n[0] || j >= n[1] || k >= n[2]) continue;
      std::int32_t& v = img.labels[img.index(i, j, k)];
      if (v != kAir) v = kSkin;
    }
}

// Islands: a voxel and axis-aligned ellipsoid semi-axes are drawn (four numbers per attempt,
// whatever the outcome, so the sequence does not depend on the image); the island is painted
// when its box grown by one voxel is all fat and inside the image.
int add_islands(LabelImage& img, const FragmentedBreastParams& p, Rng& rng) {
  const std::array<int, 3> n = img.dims;
  const double h = p.spacing_mm;
  const long long max_attempts = 60LL * p.fgt_islands + 100000;
  int placed = 0;
  for (long long attempt = 0; attempt < max_attempts && placed < p.fgt_islands; ++attempt) {
    const std::array<int, 3> c{rng.index(n[0]), rng.index(n[1]), rng.index(n[2])};
    const double size = rng.uniform();
    const Vector3d stretch{rng.uniform(0.7, 1.3), rng.uniform(0.7, 1.3), rng.uniform(0.7, 1.3)};
    if (img.at(c[0], c[1], c[2]) != kFat) continue;
    // Diameter skewed towards one voxel: h + (max - h) u^3.
    const double diameter = std::max(h, h + (p.island_max_diameter_mm - h) * size * size * size);
    const Vector3d semi = 0.5 * diameter * stretch;
    std::array<int, 3> half;
    bool room = true;
    for (int a = 0; a < 3; ++a) {
      half[a] = static_cast<int>(std::floor(semi[a] / h));
      room = room && c[a] - half[a] - 1 >= 0 && c[a] + half[a] + 1 < n[a];
    }
    for (int k = -half[2] - 1; room && k <= half[2] + 1; ++k)
      for (int j = -half[1] - 1; room && j <= half[1] + 1; ++j)
        for (int i = -half[0] - 1; room && i <= half[0] + 1; ++i)
          room = img.at(c[0] + i, c[1] + j, c[2] + k) == kFat;
    if (!room) continue;
    for (int k = -half[2]; k <= half[2]; ++k)
      for (int j = -half[1]; j <= half[1]; ++j)
        for (int i = -half[0]; i <= half[0]; ++i) {
          const double u = i * h / semi.x(), v = j * h / semi.y(), w = k * h / semi.z();
          if ((i == 0 && j == 0 && k == 0) || u * u + v * v + w * w <= 1.0)
            img.labels[img.index(c[0] + i, c[1] + j, c[2] + k)] = kFgt;
        }
    ++placed;
  }
  return placed;
}

// Diagonal contacts: one-voxel FGT islands that touch other FGT only along an edge or at a
// corner, as noisy segmentations do (separate 6-connected components, one 26-connected tissue):
// a mesher sees a non-manifold edge or vertex there. Each attempt draws an FGT voxel (from the
// list of them in scan order: 4 bytes per FGT voxel) and one of its 20 diagonal neighbours.
int add_diagonal_contacts(LabelImage& img, int wanted, Rng& rng) {
  if (wanted == 0) return 0;
  static const std::array<std::array<int, 3>, 20> kDiagonal = [] {
    std::array<std::array<int, 3>, 20> out{};
    int n = 0;
    for (int k = -1; k <= 1; ++k)
      for (int j = -1; j <= 1; ++j)
        for (int i = -1; i <= 1; ++i)
          if ((i != 0) + (j != 0) + (k != 0) >= 2) out[n++] = {i, j, k};
    return out;
  }();
  const std::array<int, 3> n = img.dims;
  std::vector<std::uint32_t> fgt;  // at most 60 million voxels: fits
  for (std::size_t v = 0; v < img.labels.size(); ++v)
    if (img.labels[v] == kFgt) fgt.push_back(static_cast<std::uint32_t>(v));
  if (fgt.empty()) return 0;
  const long long max_attempts = 400LL * wanted + 100000;
  int placed = 0;
  for (long long attempt = 0; attempt < max_attempts && placed < wanted; ++attempt) {
    const std::size_t v = fgt[static_cast<std::size_t>(rng.uniform() * fgt.size())];
    const std::array<int, 3>& d = kDiagonal[rng.index(20)];
    const int i = static_cast<int>(v % n[0]) + d[0];
    const int j = static_cast<int>(v / n[0] % n[1]) + d[1];
    const int k = static_cast<int>(v / (static_cast<std::size_t>(n[0]) * n[1])) + d[2];
    if (i < 1 || j < 1 || k < 1 || i >= n[0] - 1 || j >= n[1] - 1 || k >= n[2] - 1) continue;
    if (img.at(i, j, k) != kFat) continue;
    if (img.at(i - 1, j, k) != kFat || img.at(i + 1, j, k) != kFat || img.at(i, j - 1, k) != kFat ||
        img.at(i, j + 1, k) != kFat || img.at(i, j, k - 1) != kFat || img.at(i, j, k + 1) != kFat)
      continue;
    img.labels[img.index(i, j, k)] = kFgt;  // not added to the list: contacts touch old FGT only
    ++placed;
  }
  return placed;
}

}  // namespace

void check_fragmented_breast_params(const FragmentedBreastParams& p,
                                    const std::function<std::string(const char*)>& where) {
  const ParamBounds bounds(where);
  auto fail = [&](const char* key, const std::string& rule) { bounds.fail(key, rule); };
  auto range = [&](const char* key, double v, double lo, double hi) { bounds.range(key, v, lo, hi); };
  if (p.seed > 2147483647u) fail("seed", "must be an integer in [0, 2147483647]");
  range("spacing_mm", p.spacing_mm, 0.1, 2.0);
  for (int a = 0; a < 3; ++a) range("size_mm", p.size_mm[a], 20.0, 600.0);
  double voxels = 1.0;
  for (int a = 0; a < 3; ++a) voxels *= std::max(1.0, std::round(p.size_mm[a] / p.spacing_mm));
  if (voxels > kMaxVoxels) {
    std::ostringstream msg;
    msg << "size_mm / spacing_mm gives " << voxels << " voxels, more than 60 million";
    fail("size_mm", msg.str());
  }
  range("skin_thickness_mm", p.skin_thickness_mm, p.spacing_mm, 5.0);
  range("vessel_max_diameter_mm", p.vessel_max_diameter_mm, 0.1, 5.0);
  range("vessel_min_diameter_mm", p.vessel_min_diameter_mm, 0.1, p.vessel_max_diameter_mm);
  range("fgt_islands", p.fgt_islands, 0, 200000);
  range("fgt_diagonal_contacts", p.fgt_diagonal_contacts, 0, 100000);
  range("island_max_diameter_mm", p.island_max_diameter_mm, 0.0, 10.0);
  range("tumor_diameter_mm", p.tumor_diameter_mm, 1.0, std::min(60.0, 0.3 * p.size_mm.minCoeff()));
}

FragmentedBreastParams parse_fragmented_breast_params(YamlMap& map) {
  FragmentedBreastParams p;
  p.seed = static_cast<std::uint32_t>(map.integer("seed", static_cast<int>(p.seed)));
  p.spacing_mm = map.number("spacing_mm", p.spacing_mm);
  const YAML::Node size = map.raw("size_mm");
  if (size.IsDefined() && !size.IsNull()) {
    bool ok = size.IsSequence() && size.size() == 3;
    for (std::size_t a = 0; ok && a < 3; ++a)
      ok = YAML::convert<double>::decode(size[a], p.size_mm[a]) && std::isfinite(p.size_mm[a]);
    if (!ok) throw InputError(map.where("size_mm") + ": expected a list of 3 numbers, got " + YAML::Dump(size));
  }
  p.skin_thickness_mm = map.number("skin_thickness_mm", p.skin_thickness_mm);
  p.vessel_max_diameter_mm = map.number("vessel_max_diameter_mm", p.vessel_max_diameter_mm);
  p.vessel_min_diameter_mm = map.number("vessel_min_diameter_mm", p.vessel_min_diameter_mm);
  p.fgt_islands = map.integer("fgt_islands", p.fgt_islands);
  p.fgt_diagonal_contacts = map.integer("fgt_diagonal_contacts", p.fgt_diagonal_contacts);
  p.island_max_diameter_mm = map.number("island_max_diameter_mm", p.island_max_diameter_mm);
  p.tumor_diameter_mm = map.number("tumor_diameter_mm", p.tumor_diameter_mm);
  check_fragmented_breast_params(p, [&](const char* key) { return map.where(key); });
  return p;
}

void fragmented_breast_params_to_yaml(const FragmentedBreastParams& p, YAML::Emitter& out) {
  out << YAML::BeginMap << YAML::Key << "seed" << YAML::Value << p.seed;
  out << YAML::Key << "spacing_mm" << YAML::Value << p.spacing_mm;
  out << YAML::Key << "size_mm" << YAML::Value << YAML::Flow << YAML::BeginSeq << p.size_mm.x()
      << p.size_mm.y() << p.size_mm.z() << YAML::EndSeq;
  out << YAML::Key << "skin_thickness_mm" << YAML::Value << p.skin_thickness_mm;
  out << YAML::Key << "vessel_max_diameter_mm" << YAML::Value << p.vessel_max_diameter_mm;
  out << YAML::Key << "vessel_min_diameter_mm" << YAML::Value << p.vessel_min_diameter_mm;
  out << YAML::Key << "fgt_islands" << YAML::Value << p.fgt_islands;
  out << YAML::Key << "fgt_diagonal_contacts" << YAML::Value << p.fgt_diagonal_contacts;
  out << YAML::Key << "island_max_diameter_mm" << YAML::Value << p.island_max_diameter_mm;
  out << YAML::Key << "tumor_diameter_mm" << YAML::Value << p.tumor_diameter_mm << YAML::EndMap;
}

LabelImage make_fragmented_breast(const FragmentedBreastParams& p) {
  auto where = [](const char* key) { return std::string("phantom parameter fragmented_breast.") + key; };
  check_fragmented_breast_params(p, where);
  LabelImage img = make_grid(p);
  img.labels.assign(img.voxel_count(), kAir);
  const Geometry g(p);
  // One stream in a fixed order: vessels, islands, diagonal contacts (the counts come last, so
  // changing them leaves everything before unchanged). The clip has its own seed.
  Rng rng(p.seed);
  label_body(img, g);
  add_tumor(img, g, p.tumor_diameter_mm);
  paint_tubes(img, vessel_tree(img, g, 0.5 * p.vessel_max_diameter_mm, 0.5 * p.vessel_min_diameter_mm, rng));
  add_skin(img, p.skin_thickness_mm);
  add_tiny_tissue(img, kFat, hard_label::kClip, p.seed + 7);
  const int placed = add_islands(img, p, rng);
  if (placed < p.fgt_islands)
    throw InputError(where("fgt_islands") + ": only " + std::to_string(placed) + " of " +
                     std::to_string(p.fgt_islands) + " islands fit in the fat; ask fewer or a larger size_mm");
  const int contacts = add_diagonal_contacts(img, p.fgt_diagonal_contacts, rng);
  if (contacts < p.fgt_diagonal_contacts)
    throw InputError(where("fgt_diagonal_contacts") + ": only " + std::to_string(contacts) + " of " +
                     std::to_string(p.fgt_diagonal_contacts) + " contacts found room; ask fewer");
  return img;
}

}  // namespace tissuemesh
