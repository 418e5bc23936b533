// Bit-reproducible random numbers and trigonometry for the label-map generators
// (fragmented_breast, folded_layers, no_background).
//
// Same seed -> same numbers on every IEEE-754 platform and standard library: the raw std::mt19937
// output is converted here (the std distributions are implementation-defined), sin/cos come from a
// Taylor series (libm may differ in the last bit), and the lattice noise hashes integers instead
// of drawing a table. Only + - * / sqrt floor are used. Callers draw in separate statements or
// braced lists: the evaluation order of function arguments is unspecified.
#pragma once

#include <Eigen/Core>

#include <cmath>
#include <cstdint>
#include <random>

namespace tissuemesh::phantom_random {

constexpr double kPi = 3.14159265358979323846;

/// sin and cos of x (radians), reduced to [-pi, pi], by a Taylor series converged to double.
inline void sin_cos(double x, double& s, double& c) {
  x -= 2.0 * kPi * std::floor(x / (2.0 * kPi) + 0.5);
  s = c = 0.0;
  double term = 1.0;  // x^n / n!
  for (int n = 0; n < 40; ++n) {
    (n % 2 ? s : c) += (n % 4 < 2 ? term : -term);
    term *= x / (n + 1);
  }
}

inline double sine(double x) {
  double s, c;
  sin_cos(x, s, c);
  return s;
}

/// Uniform numbers from raw mt19937 output.
class Rng {
 public:
  explicit Rng(std::uint32_t seed) : gen_(seed) {}
  double uniform() { return static_cast<double>(gen_()) * (1.0 / 4294967296.0); }  // [0, 1)
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }
  /// Integer in [0, n).
  int index(int n) { return static_cast<int>(uniform() * n); }
  /// Isotropic unit vector (rejection from the cube: no trigonometry).
  Eigen::Vector3d unit_vector() {
    for (;;) {
      const Eigen::Vector3d v{uniform(-1, 1), uniform(-1, 1), uniform(-1, 1)};
      const double n2 = v.squaredNorm();
      if (n2 > 1e-4 && n2 <= 1.0) return v / std::sqrt(n2);
    }
  }

 private:
  std::mt19937 gen_;
};

/// The hashed value in [-1, 1] of corner `corner` (bit a: +1 along axis a) of the lattice cell
/// whose lowest corner is `f` (integer coordinates), hashing from the start value `h`; `weight`
/// gets the corner's smoothstep trilinear weight from the cell-local weights `w`.
inline double lattice_corner(std::uint32_t h, const Eigen::Vector3d& f, const Eigen::Array3d& w, int corner,
                             double& weight) {
  weight = 1.0;
  for (int a = 0; a < 3; ++a) {
    const int bit = (corner >> a) & 1;
    h ^= static_cast<std::uint32_t>(static_cast<std::int64_t>(f[a]) + bit) * 0x85EBCA6Bu;
    h = (h ^ (h >> 15)) * 0xC2B2AE35u;
    h ^= h >> 13;
    weight *= bit ? w[a] : 1.0 - w[a];
  }
  return static_cast<double>(h) * (2.0 / 4294967296.0) - 1.0;
}

/// Value noise in [-1, 1] on a lattice of cell size `cell_mm`: smoothstep-weighted trilinear
/// interpolation of hashed lattice values (stateless: the same at every point, in any order).
inline double lattice_noise(const Eigen::Vector3d& p, double cell_mm, std::uint32_t seed) {
  const Eigen::Vector3d g = p / cell_mm;
  const Eigen::Vector3d f = g.array().floor();
  const Eigen::Array3d t = (g - f).array();
  const Eigen::Array3d w = t * t * (3.0 - 2.0 * t);
  double total = 0.0;
  for (int corner = 0; corner < 8; ++corner) {
    double weight;
    const double value = lattice_corner(seed * 0x9E3779B9u + 0x7F4A7C15u, f, w, corner, weight);
    total += weight * value;
  }
  return total;
}

}  // namespace tissuemesh::phantom_random
