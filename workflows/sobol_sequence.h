// Sobol' low-discrepancy points in [0, 1)^d (Sobol', USSR Comput. Math. Math. Phys. 7, 1967), with
// the direction numbers of Joe & Kuo (SIAM J. Sci. Comput. 30:2635, 2008, file new-joe-kuo-6.21201;
// dimensions 1..kMaxSobolDimensions), Gray-code order, 32 bits, the first point (all zeros)
// skipped. Randomised by a seeded digital shift (each dimension's integers XOR one random 32-bit
// word, std::mt19937_64): the points keep their stratification and differ by seed. Not Owen's
// scrambling.
#pragma once

#include <cstdint>
#include <vector>

namespace tissuemesh {

constexpr int kMaxSobolDimensions = 21;

/// n points of dimension d (1 <= d <= kMaxSobolDimensions, else std::invalid_argument), row-major
/// (point i, coordinate j at [i * d + j]). seed 0 = no shift (the plain sequence).
std::vector<double> sobol_points(int n, int d, std::uint64_t seed);

}  // namespace tissuemesh
