// Background fill and the tiny tissue; no_background.h states the contract.
#include "image/no_background.h"

#include "core/errors.h"
#include "image/phantom_random.h"

#include <array>
#include <string>
#include <vector>

namespace tissuemesh {
namespace {

// Index offsets of the voxels within `radius` voxels of the centre voxel.
std::vector<std::array<int, 3>> ball_offsets(int radius) {
  std::vector<std::array<int, 3>> out;
  for (int k = -radius; k <= radius; ++k)
    for (int j = -radius; j <= radius; ++j)
      for (int i = -radius; i <= radius; ++i)
        if (i * i + j * j + k * k <= radius * radius) out.push_back({i, j, k});
  return out;
}

}  // namespace

std::size_t fill_background(LabelImage& image, std::int32_t fill) {
  std::size_t changed = 0;
  for (std::int32_t& v : image.labels)
    if (v == 0) {
      v = fill;
      ++changed;
    }
  return changed;
}

std::size_t add_tiny_tissue(LabelImage& image, std::int32_t host, std::int32_t label,
                            std::uint32_t seed) {
  constexpr int r = kTinyTissueRadiusVoxels;
  const auto ball = ball_offsets(r);
  const auto guard = ball_offsets(r + 1);
  const std::array<int, 3> n = image.dims;
  auto fits = [&](int i, int j, int k) {
    if (i < r + 1 || j < r + 1 || k < r + 1 || i >= n[0] - r - 1 || j >= n[1] - r - 1 ||
        k >= n[2] - r - 1)
      return false;
    for (const auto& o : guard)
      if (image.at(i + o[0], j + o[1], k + o[2]) != host) return false;
    return true;
  };
  auto paint = [&](int i, int j, int k) {
    for (const auto& o : ball) image.labels[image.index(i + o[0], j + o[1], k + o[2])] = label;
    return ball.size();
  };
  // Seeded tries first (a place anywhere in the host, not always the first in scan order); the
  // scan is the fallback for a host too small to be hit by chance.
  phantom_random::Rng rng(seed);
  for (int attempt = 0; attempt < 200000; ++attempt) {
    const int i = rng.index(n[0]);
    const int j = rng.index(n[1]);
    const int k = rng.index(n[2]);
    if (image.at(i, j, k) == host && fits(i, j, k)) return paint(i, j, k);
  }
  for (int k = 0; k < n[2]; ++k)
    for (int j = 0; j < n[1]; ++j)
      for (int i = 0; i < n[0]; ++i)
        if (image.at(i, j, k) == host && fits(i, j, k)) return paint(i, j, k);
  throw MeshingError("no room for a tiny tissue (label " + std::to_string(label) +
                     ") inside label " + std::to_string(host) + ": no ball of " +
                     std::to_string(2 * r + 3) + " voxels across holds only that label");
}

}  // namespace tissuemesh
