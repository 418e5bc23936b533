#include "workflows/sobol_sequence.h"

#include <array>
#include <random>
#include <stdexcept>

namespace tissuemesh {

namespace {

struct DirectionRow {
  int s, a;
  std::array<unsigned, 7> m;
};

// Joe & Kuo, new-joe-kuo-6.21201, dimensions 2..21 (dimension 1 is van der Corput).
constexpr DirectionRow kRows[] = {
    {1, 0, {1}},           {2, 1, {1, 3}},        {3, 1, {1, 3, 1}},          {3, 2, {1, 1, 1}},
    {4, 1, {1, 1, 3, 3}},  {4, 4, {1, 3, 5, 13}}, {5, 2, {1, 1, 5, 5, 17}},   {5, 4, {1, 1, 5, 5, 5}},
    {5, 7, {1, 1, 7, 11, 19}}, {5, 11, {1, 1, 5, 1, 1}}, {5, 13, {1, 1, 1, 3, 11}}, {5, 14, {1, 3, 5, 5, 31}},
    {6, 1, {1, 3, 3, 9, 7, 49}}, {6, 13, {1, 1, 1, 15, 21, 21}}, {6, 16, {1, 3, 1, 13, 27, 49}},
    {6, 19, {1, 1, 1, 15, 7, 5}}, {6, 22, {1, 3, 1, 15, 13, 25}}, {6, 25, {1, 1, 5, 5, 19, 61}},
    {7, 1, {1, 3, 7, 11, 23, 15, 103}}, {7, 4, {1, 3, 7, 13, 13, 15, 69}}};
static_assert(sizeof(kRows) / sizeof(kRows[0]) == kMaxSobolDimensions - 1, "one row per dimension after the first");

constexpr int kBits = 32;

std::array<std::uint32_t, kBits> directions(int dim) {
  std::array<std::uint32_t, kBits> v{};
  if (dim == 0) {
    for (int i = 0; i < kBits; ++i) v[i] = 1u << (kBits - 1 - i);
    return v;
  }
  const DirectionRow& r = kRows[dim - 1];
  for (int i = 0; i < r.s; ++i) v[i] = r.m[i] << (kBits - 1 - i);
  for (int i = r.s; i < kBits; ++i) {
    v[i] = v[i - r.s] ^ (v[i - r.s] >> r.s);
    for (int k = 1; k < r.s; ++k)
      if ((r.a >> (r.s - 1 - k)) & 1u) v[i] ^= v[i - k];
  }
  return v;
}

}  // namespace

std::vector<double> sobol_points(int n, int d, std::uint64_t seed) {
  if (d < 1 || d > kMaxSobolDimensions) throw std::invalid_argument("sobol_points: dimension out of range");
  if (n < 0) throw std::invalid_argument("sobol_points: negative count");
  std::vector<std::array<std::uint32_t, kBits>> v(d);
  std::vector<std::uint32_t> shift(d, 0), x(d, 0);
  for (int j = 0; j < d; ++j) v[j] = directions(j);
  if (seed != 0) {
    std::mt19937_64 rng(seed);
    for (int j = 0; j < d; ++j) shift[j] = static_cast<std::uint32_t>(rng() >> 32);
  }
  std::vector<double> out(static_cast<std::size_t>(n) * d);
  for (int i = 0; i < n; ++i) {
    // Gray code: point i + 1 differs from point i in the direction of the lowest zero bit of i.
    int c = 0;
    for (unsigned k = static_cast<unsigned>(i); k & 1u; k >>= 1) ++c;
    for (int j = 0; j < d; ++j) {
      x[j] ^= v[j][c];
      out[static_cast<std::size_t>(i) * d + j] = static_cast<double>(x[j] ^ shift[j]) / 4294967296.0;
    }
  }
  return out;
}

}  // namespace tissuemesh
