// Built-in breast phantom; phantom.h describes the geometry and the contract.
//
// FGT capsules are rasterised into a distance buffer over their own bounding boxes, so that the
// one pass over all voxels (body, layers, FGT) never loops over primitives; tumour and islands
// are painted over their boxes; skin comes from an exact anisotropic distance transform.
// Bit-for-bit determinism across platforms: raw std::mt19937 output is converted here (the std
// distributions are implementation-defined) and only exact IEEE operations (+ - * / sqrt floor)
// are used, with sin/cos from a Taylor series (libm may differ in the last bit). Clang may fuse
// a*b+c into an FMA that rounds differently: the pragma forbids it (GCC does not in ISO mode).
#ifdef __clang__
#pragma STDC FP_CONTRACT OFF
#endif

#include "image/phantom.h"
#include "image/param_bounds.h"

#include "core/errors.h"
#include "image/phantom_random.h"

#include <Eigen/Dense>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <random>
#include <sstream>
#include <vector>

namespace tissuemesh {
namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;

constexpr double kPi = 3.14159265358979323846;
constexpr double kChestFatMm = 8.0;          // subcutaneous fat between chest skin and muscle
constexpr double kChestRadiusLrMm = 250.0;   // chest wall curvature, left-right (barrel-shaped)
constexpr double kChestRadiusSiMm = 500.0;   // chest wall curvature, superior-inferior
constexpr double kFilletMm = 10.0;           // smooth-union width: no sharp crease at the fold
constexpr double kBreastTaper = 0.12;        // lateral radii shrink 12% base to nipple: conical
constexpr double kBreastIrregularity = 0.06; // max relative radial deformation of the breast
constexpr double kLateralMarginMm = 15.0;    // chest visible beyond the breast, L-R and S-I
constexpr double kAirMarginMm = 5.0;         // air around the breast in the field of view
constexpr double kThoraxMinMm = 8.0;         // thorax visible behind the muscle at every corner
constexpr double kFgtNoiseMm = 1.5;          // FGT surface perturbation: lobular, not smooth tubes
constexpr double kTumorModulation = 0.18;    // +-18% low-order lobulation of the tumour radius
constexpr double kIslandModulation = 0.15;   // islands are slightly oblate/prolate, not spheres
constexpr double kMaxVoxels = 60e6;          // ~0.5 GB of buffers, far beyond a useful phantom
constexpr float kFar = std::numeric_limits<float>::infinity();

// sin and cos of x (radians) by Taylor series after reduction to [-pi, pi]; see the file comment.
using phantom_random::Rng;
using phantom_random::sin_cos;

double legendre(int l, double t) {
  double t2 = t * t;
  if (l == 2) return 0.5 * (3.0 * t2 - 1.0);
  if (l == 3) return 0.5 * t * (5.0 * t2 - 3.0);
  return 0.125 * (35.0 * t2 * t2 - 30.0 * t2 + 3.0);
}

// Sum of random Legendre terms scaled so that its largest magnitude over 512 evenly spread
// directions is 1: a smooth random function on the unit sphere that uses its full +-1 range
// (random weights alone mostly cancel, leaving a barely modulated sphere).
struct SphereModulation {
  struct Term {
    int degree;
    Vector3d axis;
    double weight;
  };
  std::vector<Term> terms;

  SphereModulation(Rng& rng, std::initializer_list<int> degrees) {
    for (int l : degrees) terms.push_back({l, rng.unit_vector(), rng.uniform(-1.0, 1.0)});
    constexpr int kDirections = 512;
    double largest = 0.0;
    for (int n = 0; n < kDirections; ++n) {  // Fibonacci sphere
      double z = 1.0 - 2.0 * (n + 0.5) / kDirections, s, c;
      sin_cos(n * kPi * (3.0 - std::sqrt(5.0)), s, c);
      double rxy = std::sqrt(1.0 - z * z);
      largest = std::max(largest, std::abs((*this)(Vector3d(rxy * c, rxy * s, z))));
    }
    for (Term& t : terms) t.weight /= largest;
  }
  double operator()(const Vector3d& u) const {
    double sum = 0.0;
    for (const Term& t : terms) sum += t.weight * legendre(t.degree, u.dot(t.axis));
    return sum;
  }
};

// Value noise in [-1, 1]: smoothstep-weighted trilinear interpolation of hashed lattice values,
// two octaves (5 and 2.5 mm). Hashing instead of a random table: stateless, same everywhere.
double value_noise(const Vector3d& p, std::uint32_t seed) {
  double total = 0.0;
  for (int octave = 0; octave < 2; ++octave) {
    const Vector3d g = p / (octave == 0 ? 5.0 : 2.5);
    const Vector3d f = g.array().floor();
    const Eigen::Array3d t = (g - f).array();
    const Eigen::Array3d w = t * t * (3.0 - 2.0 * t);
    for (int corner = 0; corner < 8; ++corner) {
      double weight;
      const double value = phantom_random::lattice_corner((seed + octave) * 0x9E3779B9u, f, w, corner, weight);
      // The octave factor is a power of two: multiplying it last rounds exactly as first.
      total += (octave == 0 ? 1.0 : 0.5) * weight * value;
    }
  }
  return total / 1.5;
}

// The breast: tapered half-ellipsoid with a low-order random radial deformation, centred on the
// base centre (the patient-frame origin).
struct BreastShape {
  double a, c, depth;  // semi-axes (mm): left-right, superior-inferior, anterior protrusion
  SphereModulation irregularity;

  BreastShape(const PhantomParams& p, Rng& rng)
      : a(0.5 * p.breast_width_mm),
        c(0.5 * p.breast_height_mm),
        depth(p.breast_depth_mm),
        irregularity(rng, {2, 3, 3, 4}) {}

  // Radial signed distance (mm, < 0 inside) to the surface rho(p) = rho0 of the tapered
  // ellipsoid radius function rho; rho0 = 1 + irregularity unless given. It is the distance
  // along the ray from the origin: not Euclidean, but close for this rounded, nearly convex
  // shape and exact in sign; it only drives the fillet and the tumour-placement check.
  double distance(const Vector3d& p, double rho0 = 0.0) const {
    const double r = p.norm();
    if (r < 1e-9) return -std::min({a, c, depth});
    if (rho0 == 0.0) rho0 = 1.0 + kBreastIrregularity * irregularity(p / r);
    const double g = 1.0 - kBreastTaper * std::clamp(-p.y() / depth, 0.0, 1.0);
    const double rho = std::sqrt(p.x() * p.x() / (a * a * g * g) +
                                 p.y() * p.y() / (depth * depth) + p.z() * p.z() / (c * c * g * g));
    return r * (rho - rho0) / rho;
  }
  // Point at depth fraction Y (0 chest wall, 1 nipple), fraction q of the (worst-case) local
  // half-width, angle phi about the anterior axis: keeps structures inside any breast size.
  Vector3d point(double Y, double q, double phi) const {
    double s, co;
    sin_cos(phi, s, co);
    double w = std::sqrt(std::max(0.0, 1.0 - Y * Y)) * (1.0 - kBreastTaper * Y) *
               (1.0 - kBreastIrregularity);
    return {q * co * a * w, -Y * depth, q * s * c * w};
  }
};

// Chest wall: anterior muscle surface y = kappa(x, z) through the origin, curving posteriorly.
double chest_kappa(double x, double z) {
  return x * x / (2.0 * kChestRadiusLrMm) + z * z / (2.0 * kChestRadiusSiMm);
}
// First-order signed distance |f| / |grad f| (< 0 inside) to the chest skin y = kappa - fat.
double chest_distance(const Vector3d& p) {
  double gx = p.x() / kChestRadiusLrMm, gz = p.z() / kChestRadiusSiMm;
  return (chest_kappa(p.x(), p.z()) - kChestFatMm - p.y()) / std::sqrt(1.0 + gx * gx + gz * gz);
}

struct Capsule {  // segment a-b swept by a ball of radius r (a sphere when a == b)
  Vector3d a, b;
  double r;
  double distance(const Vector3d& p) const {
    const Vector3d ab = b - a;
    const double t = a == b ? 0.0 : std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
    return (p - a - t * ab).norm() - r;
  }
};

// Lobulated tumour with a few short spicules: radius R (1 + m(u)) + sum of narrow bumps.
struct Tumor {
  Vector3d center;
  double radius;
  SphereModulation lobulation;
  std::vector<Vector3d> spicule_dir;
  std::vector<double> spicule_len;
  double reach = 0.0;  // largest surface radius
  static constexpr double kSpiculeCos = 0.95;  // half-angle ~18 degrees

  Tumor(const PhantomParams& p, Rng& rng)
      : center(p.tumor_center_mm), radius(0.5 * p.tumor_diameter_mm),
        lobulation(rng, {2, 3, 3, 4}) {
    for (int n = 2 + rng.index(2); n > 0; --n) {
      spicule_dir.push_back(rng.unit_vector());
      spicule_len.push_back(radius * rng.uniform(0.5, 0.9));
      reach = std::max(reach, radius * (1.0 + kTumorModulation) + spicule_len.back());
    }
  }
  double surface_radius(const Vector3d& u) const {
    double r = radius * (1.0 + kTumorModulation * lobulation(u));
    for (std::size_t n = 0; n < spicule_dir.size(); ++n) {
      double w = std::max(0.0, (u.dot(spicule_dir[n]) - kSpiculeCos) / (1.0 - kSpiculeCos));
      r += spicule_len[n] * w * w * w;
    }
    return r;
  }
};

// Ducts from behind the nipple towards the chest wall: 10-15 main ducts of three thinning
// segments, 2-3 side branches ending in a lobule at each joint, a lobule cluster at each end,
// and a duct plus lobule around the tumour so that it always sits inside the main FGT.
std::vector<Capsule> fgt_tree(const BreastShape& breast, const Tumor& tumor, Rng& rng) {
  const double y_start = 1.0 - std::min(12.0, 0.25 * breast.depth) / breast.depth;
  const Vector3d start = breast.point(y_start, 0.0, 0.0);
  std::vector<Capsule> out{{start, start, 7.0}};
  const int ducts = 10 + rng.index(6);
  for (int d = 0; d < ducts; ++d) {
    double phi = 2.0 * kPi * (d + rng.uniform(-0.3, 0.3)) / ducts;
    double y_end = rng.uniform(0.2, 0.45), q_end = rng.uniform(0.4, 0.7);
    Vector3d prev = start;
    for (int seg = 1; seg <= 3; ++seg) {
      double t = seg / 3.0;
      double Y = y_start + (y_end - y_start) * t;
      // Fans out early, then runs towards the wall; inner joints wander a little.
      double q = q_end * t * (1.6 - 0.6 * t) + (seg < 3 ? rng.uniform(-0.06, 0.06) : 0.0);
      double ph = phi + (seg < 3 ? rng.uniform(-0.2, 0.2) : 0.0);
      Vector3d joint = breast.point(Y, q, ph);
      out.push_back({prev, joint, 4.6 - 0.6 * seg + rng.uniform(-0.3, 0.3)});
      if (seg < 3) {
        for (int b = 2 + rng.index(2); b > 0; --b) {
          const double side = rng.uniform() < 0.5 ? -1.0 : 1.0;
          const double tip_y = Y - rng.uniform(0.05, 0.18);
          const double tip_q = std::min(0.8, q + rng.uniform(0.12, 0.3));
          const Vector3d tip = breast.point(tip_y, tip_q, ph + side * rng.uniform(0.25, 0.6));
          out.push_back({joint, tip, rng.uniform(1.8, 2.4)});
          out.push_back({tip, tip, rng.uniform(4.0, 6.0)});
        }
      }
      prev = joint;
    }
    for (int l = 3 + rng.index(2); l > 0; --l) {
      const Vector3d dir = rng.unit_vector();
      const Vector3d c = prev + dir * rng.uniform(0.0, 5.0);
      out.push_back({c, c, rng.uniform(4.5, 6.5)});
    }
  }
  out.push_back({start, tumor.center, 3.0});
  out.push_back({tumor.center, tumor.center, tumor.radius + 3.0});
  return out;
}

// Header of the phantom image (labels left empty): axes i Right, j Anterior, k Superior rotated
// about the superior axis; the field of view is a box in that rotated frame.
LabelImage phantom_grid(const PhantomParams& p) {
  LabelImage g;
  double s, c;
  sin_cos(p.oblique_deg * kPi / 180.0, s, c);
  // Rotation by the angle about +z times diag(-1, -1, 1) (i Right, j Anterior, k Superior).
  g.direction << -c, s, 0.0, -s, -c, 0.0, 0.0, 0.0, 1.0;
  // Breast bound: ellipsoid of semi-axes (a, depth, c) grown by the irregularity; its extent
  // along unit w is sqrt(sum (s_a w_a)^2).
  const Vector3d semi = Vector3d(0.5 * p.breast_width_mm, p.breast_depth_mm,
                                 0.5 * p.breast_height_mm) * (1.0 + kBreastIrregularity);
  auto extent = [&](const Vector3d& w) { return semi.cwiseProduct(w).norm(); };
  const double half_i = std::max(0.5 * p.breast_width_mm + kLateralMarginMm,
                                 extent(g.direction.col(0)) + kAirMarginMm);
  const double half_k = std::max(0.5 * p.breast_height_mm + kLateralMarginMm,
                                 extent(g.direction.col(2)) + kAirMarginMm);
  const double anterior = extent(g.direction.col(1)) + kAirMarginMm;
  // Posterior reach: thorax behind the (laterally receding) muscle at every posterior corner.
  // y at the posterior face is c*back - s*xi; x there is at most half_i + |s|*back.
  double back = p.muscle_thickness_mm + kThoraxMinMm;
  for (int it = 0; it < 4; ++it) {
    double kappa_max = chest_kappa(half_i + std::abs(s) * back, half_k);
    back = (kappa_max + p.muscle_thickness_mm + kThoraxMinMm + std::abs(s) * half_i) / c;
  }
  const Vector3d lo(-half_i, -back, -half_k), hi(half_i, anterior, half_k);
  Vector3d start;
  for (int a = 0; a < 3; ++a) {
    double h = p.spacing_mm[a];
    g.dims[a] = static_cast<int>(std::ceil((hi[a] - lo[a]) / h)) + 1;
    // Centre the voxel centres on the box along i and k; j starts at the posterior face.
    start[a] = a == 1 ? lo[a] : -0.5 * (g.dims[a] - 1) * h;
  }
  g.origin = g.direction * start;
  g.spacing = p.spacing_mm;
  return g;
}

// The scalar parameters: YAML key, field, bounds. skin_thickness_mm is also bounded below by half
// the smallest spacing, checked apart.
struct ScalarParam {
  const char* key;
  double PhantomParams::*field;
  double lo, hi;
};
constexpr ScalarParam kScalars[] = {
    {"oblique_deg", &PhantomParams::oblique_deg, -30.0, 30.0},
    {"breast_width_mm", &PhantomParams::breast_width_mm, 40.0, 250.0},
    {"breast_height_mm", &PhantomParams::breast_height_mm, 40.0, 250.0},
    {"breast_depth_mm", &PhantomParams::breast_depth_mm, 20.0, 200.0},
    {"skin_thickness_mm", &PhantomParams::skin_thickness_mm, 0.05, 10.0},
    {"muscle_thickness_mm", &PhantomParams::muscle_thickness_mm, 2.0, 40.0},
    {"tumor_diameter_mm", &PhantomParams::tumor_diameter_mm, 2.0, 60.0}};

// Bounds of every parameter in one place; `where(key)` prefixes the message (file and key).
void check_params(const PhantomParams& p, const std::function<std::string(const char*)>& where) {
  const ParamBounds bounds(where);
  auto fail = [&](const char* key, const std::string& rule) { bounds.fail(key, rule); };
  auto range = [&](const char* key, double v, double lo, double hi) { bounds.range(key, v, lo, hi); };
  auto format_vec = [](const Vector3d& v) {
    std::ostringstream out;
    out << "(" << v.x() << ", " << v.y() << ", " << v.z() << ")";
    return out.str();
  };
  if (!((p.spacing_mm.array() >= 0.1) && (p.spacing_mm.array() <= 5.0)).all())  // NaN fails too
    fail("spacing_mm", "each spacing must be in [0.1, 5] mm, got " + format_vec(p.spacing_mm));
  if (p.seed > 2147483647u) fail("seed", "must be an integer in [0, 2147483647]");
  for (const ScalarParam& s : kScalars) range(s.key, p.*s.field, s.lo, s.hi);
  range("skin_thickness_mm", p.skin_thickness_mm, 0.5 * p.spacing_mm.minCoeff(), 10.0);
  range("fgt_islands", p.fgt_islands, 0, 20);
  // Worst case over every seed: the breast shrunk by its full irregularity.
  Rng rng(p.seed);
  const double depth = -BreastShape(p, rng).distance(p.tumor_center_mm, 1.0 - kBreastIrregularity);
  if (!p.tumor_center_mm.allFinite() || !(p.tumor_center_mm.y() < 0.0) ||
      !(depth >= p.skin_thickness_mm + 2.0)) {
    fail("tumor_center_mm", format_vec(p.tumor_center_mm) + " is not inside the breast (skin " +
                                "thickness + 2 mm under its surface, anterior to the chest wall)");
  }
  const LabelImage g = phantom_grid(p);
  if (static_cast<double>(g.dims[0]) * g.dims[1] * g.dims[2] > kMaxVoxels)
    fail("spacing_mm", format_vec(p.spacing_mm) + " gives more than 60 million voxels");
}

// Calls visit(index, physical point) for every voxel whose centre lies in the physical box
// [lo, hi]; stops when visit returns false. Returns false if it was stopped.
template <class Visit>
bool visit_box(const LabelImage& img, const Vector3d& lo, const Vector3d& hi, Visit&& visit) {
  const Matrix3d to_physical = img.index_to_physical(), to_index = to_physical.inverse();
  // Index-space bounding box of the (rotated) physical box: centre +- |M^-1| half-size.
  const Vector3d mid = to_index * (0.5 * (lo + hi) - img.origin);
  const Vector3d half = to_index.cwiseAbs() * (0.5 * (hi - lo));
  std::array<int, 3> first, last;
  for (int a = 0; a < 3; ++a) {
    first[a] = static_cast<int>(std::max(0.0, std::ceil(mid[a] - half[a])));
    last[a] = static_cast<int>(std::min(img.dims[a] - 1.0, std::floor(mid[a] + half[a])));
  }
  for (int k = first[2]; k <= last[2]; ++k)
    for (int j = first[1]; j <= last[1]; ++j)
      for (int i = first[0]; i <= last[0]; ++i)
        if (!visit(img.index(i, j, k), Vector3d(img.origin + to_physical * Vector3d(i, j, k))))
          return false;
  return true;
}

// Body, layers and FGT in one pass over all voxels. `fgt` holds the signed distance to the FGT
// primitives (kFar where farther than the noise amplitude).
void label_tissues(LabelImage& img, const PhantomParams& p, const BreastShape& breast,
                   const std::vector<float>& fgt) {
  const Matrix3d to_physical = img.index_to_physical();
  for (int k = 0; k < img.dims[2]; ++k) {
    for (int j = 0; j < img.dims[1]; ++j) {
      const Vector3d row = img.origin + to_physical * Vector3d(0.0, j, k);
      std::size_t idx = img.index(0, j, k);
      for (int i = 0; i < img.dims[0]; ++i, ++idx) {
        const Vector3d x = row + to_physical.col(0) * static_cast<double>(i);
        const double depth_behind_wall = x.y() - chest_kappa(x.x(), x.z());
        if (depth_behind_wall >= p.muscle_thickness_mm) {
          img.labels[idx] = kThorax;
        } else if (depth_behind_wall >= 0.0) {
          img.labels[idx] = kMuscle;
        } else {
          // Body = polynomial smooth minimum (Quilez) of breast and chest distances: their
          // minimum, lowered by up to kFilletMm / 4 where they are within kFilletMm (the fold).
          const double chest = chest_distance(x);
          if (chest >= 0.0) {
            const double breast_d = breast.distance(x);
            const double h = std::max(kFilletMm - std::abs(breast_d - chest), 0.0) / kFilletMm;
            if (std::min(breast_d, chest) - 0.25 * h * h * kFilletMm >= 0.0) continue;  // air
          }
          const double d = fgt[idx];
          const bool gland = d < kFgtNoiseMm &&
                             (d <= -kFgtNoiseMm || d - kFgtNoiseMm * value_noise(x, p.seed) < 0.0);
          img.labels[idx] = gland ? kFgt : kFat;
        }
      }
    }
  }
}

// Places p.fgt_islands islands where a ball around them holds only fat, and paints them.
// The ball leaves a gap of 4 largest spacings between voxel centres (3 whole voxels of fat)
// between the island and anything else; air must be farther by the skin still to come (its
// thickness plus a voxel diagonal). Throws InputError if they do not fit.
void add_islands(LabelImage& img, const PhantomParams& p, const BreastShape& breast, Rng& rng) {
  const double gap = 4.0 * p.spacing_mm.maxCoeff();
  const double skin_reach = p.skin_thickness_mm + p.spacing_mm.norm();
  int placed = 0;
  for (int attempt = 0; attempt < 4000 && placed < p.fgt_islands; ++attempt) {
    const double Y = rng.uniform(0.1, 0.85);
    const double q = 0.95 * std::sqrt(rng.uniform());  // area-uniform over the cross-section
    const Vector3d center = breast.point(Y, q, rng.uniform(0.0, 2.0 * kPi));
    const double radius = rng.uniform(1.5, 4.0);
    const Vector3d axis = rng.unit_vector();
    const double reach = radius * (1.0 + kIslandModulation) + gap;
    const Vector3d box = Vector3d::Constant(reach + skin_reach);
    const bool free = visit_box(img, center - box, center + box,
                                [&](std::size_t idx, const Vector3d& x) {
                                  const double r = (x - center).norm();
                                  return r <= reach ? img.labels[idx] == kFat
                                                    : r > reach + skin_reach ||
                                                          img.labels[idx] != kAir;
                                });
    if (!free) continue;
    visit_box(img, center - box, center + box, [&](std::size_t idx, const Vector3d& x) {
      const double r = (x - center).norm();
      const double cos_axis = r > 0.0 ? (x - center).dot(axis) / r : 1.0;
      if (r < radius * (1.0 + kIslandModulation * legendre(2, cos_axis))) img.labels[idx] = kFgt;
      return true;
    });
    ++placed;
  }
  if (placed < p.fgt_islands)
    throw InputError("phantom parameter fgt_islands: only " + std::to_string(placed) + " of " +
                     std::to_string(p.fgt_islands) + " islands fit in the breast fat; ask fewer");
}

// 1D squared Euclidean distance transform (Felzenszwalb & Huttenlocher, "Distance transforms
// of sampled functions", 2012), in place: f[p] <- min_q f[q] + h2 (p - q)^2 over the lower
// envelope of parabolas. Infinite values mark "no site". Scratch vectors are reused by callers.
struct EnvelopeScratch { std::vector<int> site; std::vector<double> height, bound; };

void distance_1d(std::vector<float>& f, double h2, EnvelopeScratch& e) {
  const int n = static_cast<int>(f.size());
  e.site.resize(n);
  e.height.resize(n);
  e.bound.resize(n + 1);
  int k = -1;
  for (int q = 0; q < n; ++q) {
    if (f[q] == kFar) continue;
    double s = -std::numeric_limits<double>::infinity();
    // Abscissa where the parabola of q overtakes that of the last site; pop hidden sites.
    while (k >= 0 && (s = ((f[q] + h2 * q * q) - (e.height[k] + h2 * e.site[k] * e.site[k])) /
                          (2.0 * h2 * (q - e.site[k]))) <= e.bound[k])
      --k;
    ++k;
    e.site[k] = q;
    e.height[k] = f[q];
    e.bound[k] = k == 0 ? -std::numeric_limits<double>::infinity() : s;
  }
  for (int q = 0, m = 0; k >= 0 && q < n; ++q) {  // k < 0: no site, the line stays infinite
    while (m < k && e.bound[m + 1] < q) ++m;
    f[q] = static_cast<float>(e.height[m] + h2 * (q - e.site[m]) * (q - e.site[m]));
  }
}

// Skin = body voxels whose box lies closer than t to the box of an air voxel. The box-to-box
// distance to air voxel a is the centre distance to the nearest voxel of a's 3x3x3
// neighbourhood (per axis max(|di| - 1, 0) * h), so it is the exact Euclidean distance
// transform of the air dilated by one voxel. Image border faces are not air: no skin there.
void add_skin(LabelImage& img, double thickness, std::vector<float>& dist) {
  const std::array<int, 3> n = img.dims;
  const std::size_t stride[3] = {1, static_cast<std::size_t>(n[0]),
                                 static_cast<std::size_t>(n[0]) * n[1]};
  // Calls fn(first voxel, stride, length) for every grid line along axis a. The inner loop runs
  // over the smaller remaining stride, so that lines along j and k share cache lines.
  auto for_lines = [&](int a, auto&& fn) {
    const int inner = a == 0 ? 1 : 0, outer = a == 2 ? 1 : 2;
    for (int u = 0; u < n[outer]; ++u)
      for (int w = 0; w < n[inner]; ++w)
        fn(u * stride[outer] + w * stride[inner], stride[a], n[a]);
  };
  dist.assign(img.voxel_count(), kFar);
  for (std::size_t v = 0; v < dist.size(); ++v)
    if (img.labels[v] == kAir) dist[v] = 0.0f;
  std::vector<float> line;
  EnvelopeScratch scratch;
  for (int pass = 0; pass < 6; ++pass) {  // passes 0-2: 3x3x3 dilation of the air; 3-5: EDT
    const int a = pass % 3;
    for_lines(a, [&](std::size_t first, std::size_t step, int len) {
      line.resize(len);
      for (int q = 0; q < len; ++q) line[q] = dist[first + q * step];
      if (pass >= 3) distance_1d(line, img.spacing[a] * img.spacing[a], scratch);
      for (int q = 0; q < len; ++q) {
        const bool next_to_air = pass < 3 && ((q > 0 && line[q - 1] == 0.0f) ||
                                              (q + 1 < len && line[q + 1] == 0.0f));
        dist[first + q * step] = next_to_air ? 0.0f : line[q];
      }
    });
  }
  const double t2 = thickness * thickness;
  for (std::size_t v = 0; v < dist.size(); ++v)
    if (img.labels[v] != kAir && dist[v] < t2) img.labels[v] = kSkin;
}

Vector3d read_vec3(YamlMap& map, const char* key, const Vector3d& fallback) {
  const YAML::Node node = map.raw(key);
  if (!node.IsDefined() || node.IsNull()) return fallback;
  Vector3d v;
  bool ok = node.IsSequence() && node.size() == 3;
  for (std::size_t a = 0; ok && a < 3; ++a)
    ok = YAML::convert<double>::decode(node[a], v[a]) && std::isfinite(v[a]);
  if (!ok) throw InputError(map.where(key) + ": expected a list of 3 numbers, got " +
                            YAML::Dump(node));
  return v;
}

}  // namespace

PhantomParams parse_phantom_params(YamlMap& map) {
  PhantomParams p;
  // A negative seed wraps above 2^31 - 1 and is reported by check_params.
  p.seed = static_cast<std::uint32_t>(map.integer("seed", static_cast<int>(p.seed)));
  p.spacing_mm = read_vec3(map, "spacing_mm", p.spacing_mm);
  p.tumor_center_mm = read_vec3(map, "tumor_center_mm", p.tumor_center_mm);
  for (const ScalarParam& s : kScalars) p.*s.field = map.number(s.key, p.*s.field);
  p.fgt_islands = map.integer("fgt_islands", p.fgt_islands);
  check_params(p, [&](const char* key) { return map.where(key); });
  p.kind = map.text("kind", p.kind);
  if (p.kind != "breast" && p.kind != "fragmented-breast" && p.kind != "folded-layers")
    throw InputError(map.where("kind") + ": unknown phantom kind '" + p.kind +
                     "' (supported: breast, fragmented-breast, folded-layers)");
  p.no_background = map.boolean("no_background", p.no_background);
  YamlMap fragmented = map.map("fragmented_breast");
  p.fragmented_breast = parse_fragmented_breast_params(fragmented);
  fragmented.finish();
  YamlMap folded = map.map("folded_layers");
  p.folded_layers = parse_folded_layers_params(folded);
  folded.finish();
  if (p.kind == "folded-layers" && p.no_background)
    check_folded_layers_params(p.folded_layers, true, [&](const char* key) { return folded.where(key); });
  return p;
}

void phantom_params_to_yaml(const PhantomParams& p, YAML::Emitter& out) {
  auto vec = [&](const char* key, const Vector3d& v) {
    out << YAML::Key << key << YAML::Value << YAML::Flow << YAML::BeginSeq << v.x() << v.y()
        << v.z() << YAML::EndSeq;
  };
  out << YAML::BeginMap << YAML::Key << "seed" << YAML::Value << p.seed;
  vec("spacing_mm", p.spacing_mm);
  vec("tumor_center_mm", p.tumor_center_mm);
  for (const ScalarParam& s : kScalars) out << YAML::Key << s.key << YAML::Value << p.*s.field;
  out << YAML::Key << "fgt_islands" << YAML::Value << p.fgt_islands;
  out << YAML::Key << "kind" << YAML::Value << p.kind;
  out << YAML::Key << "no_background" << YAML::Value << p.no_background;
  out << YAML::Key << "fragmented_breast" << YAML::Value;
  fragmented_breast_params_to_yaml(p.fragmented_breast, out);
  out << YAML::Key << "folded_layers" << YAML::Value;
  folded_layers_params_to_yaml(p.folded_layers, out);
  out << YAML::EndMap;
}

LabelImage make_breast_phantom(const PhantomParams& p) {
  check_params(p, [](const char* key) { return std::string("phantom parameter ") + key; });
  LabelImage img = phantom_grid(p);
  img.labels.assign(img.voxel_count(), kAir);

  // One stream, drawn in a fixed order: shape, tumour, FGT tree, islands. The island count
  // comes last so that changing it leaves everything else unchanged.
  Rng rng(p.seed);
  const BreastShape breast(p, rng);
  const Tumor tumor(p, rng);
  std::vector<float> field(img.voxel_count(), kFar);
  for (const Capsule& cap : fgt_tree(breast, tumor, rng)) {
    const Vector3d pad = Vector3d::Constant(cap.r + kFgtNoiseMm);
    visit_box(img, cap.a.cwiseMin(cap.b) - pad, cap.a.cwiseMax(cap.b) + pad,
              [&](std::size_t idx, const Vector3d& x) {
                field[idx] = std::min(field[idx], static_cast<float>(cap.distance(x)));
                return true;
              });
  }
  label_tissues(img, p, breast, field);

  const Vector3d reach = Vector3d::Constant(tumor.reach);
  visit_box(img, tumor.center - reach, tumor.center + reach,
            [&](std::size_t idx, const Vector3d& x) {
              if (img.labels[idx] != kFat && img.labels[idx] != kFgt) return true;
              Vector3d v = x - tumor.center;
              double r = v.norm();
              if (r == 0.0 || r < tumor.surface_radius(v / r)) img.labels[idx] = kTumor;
              return true;
            });
  add_islands(img, p, breast, rng);
  add_skin(img, p.skin_thickness_mm, field);
  return img;
}

}  // namespace tissuemesh
