// Measurements on label images shared by the hard-input tests: labels on each face of the box,
// 6-neighbour label pairs, runs of a label along axis rays, distance of a voxel to the nearest
// voxel of another label.
#pragma once

#include "core/label_image.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <set>
#include <utility>
#include <vector>

namespace tissuemesh::test {

/// Labels on each face of the box: 0 i-min, 1 i-max, 2 j-min, 3 j-max, 4 k-min, 5 k-max.
inline std::array<std::set<std::int32_t>, 6> face_labels(const LabelImage& img) {
  std::array<std::set<std::int32_t>, 6> faces;
  const auto n = img.dims;
  for (int k = 0; k < n[2]; ++k)
    for (int j = 0; j < n[1]; ++j)
      for (int i = 0; i < n[0]; ++i) {
        const std::int32_t l = img.at(i, j, k);
        if (i == 0) faces[0].insert(l);
        if (i == n[0] - 1) faces[1].insert(l);
        if (j == 0) faces[2].insert(l);
        if (j == n[1] - 1) faces[3].insert(l);
        if (k == 0) faces[4].insert(l);
        if (k == n[2] - 1) faces[5].insert(l);
      }
  return faces;
}

/// Every unordered pair of different labels that are 6-neighbours somewhere.
inline std::set<std::pair<std::int32_t, std::int32_t>> touching_pairs(const LabelImage& img) {
  std::set<std::pair<std::int32_t, std::int32_t>> pairs;
  const auto n = img.dims;
  for (int k = 0; k < n[2]; ++k)
    for (int j = 0; j < n[1]; ++j)
      for (int i = 0; i < n[0]; ++i) {
        const std::int32_t a = img.at(i, j, k);
        const std::int32_t nb[3] = {i + 1 < n[0] ? img.at(i + 1, j, k) : a,
                                    j + 1 < n[1] ? img.at(i, j + 1, k) : a,
                                    k + 1 < n[2] ? img.at(i, j, k + 1) : a};
        for (std::int32_t b : nb)
          if (b != a) pairs.insert({std::min(a, b), std::max(a, b)});
      }
  return pairs;
}

/// Lengths (voxels) of the runs of `label` along every axis ray, in both directions, that start
/// right after a voxel of `from` and end at a voxel that is neither `label` nor `from` (runs
/// cut by the image border or ending in `from` again are left out: their length is not a
/// thickness).
inline std::vector<int> runs_after(const LabelImage& img, std::int32_t from, std::int32_t label) {
  std::vector<int> runs;
  const auto n = img.dims;
  for (int axis = 0; axis < 3; ++axis) {
    const int u = (axis + 1) % 3, w = (axis + 2) % 3;
    for (int b = 0; b < n[w]; ++b)
      for (int a = 0; a < n[u]; ++a)
        for (int dir : {1, -1}) {
          std::array<int, 3> p{};
          p[u] = a;
          p[w] = b;
          auto at = [&](int q) {
            p[axis] = dir > 0 ? q : n[axis] - 1 - q;
            return img.at(p[0], p[1], p[2]);
          };
          for (int q = 1; q < n[axis]; ++q) {
            if (at(q - 1) != from || at(q) != label) continue;
            int end = q;
            while (end < n[axis] && at(end) == label) ++end;
            if (end < n[axis] && at(end) != from) runs.push_back(end - q);
            q = end - 1;
          }
        }
  }
  return runs;
}

/// Distance (mm) from the centre of voxel (i, j, k) to the nearest voxel centre whose label is
/// not `label`, searched within `window` voxels (returns +inf when there is none that close).
inline double distance_to_other(const LabelImage& img, int i, int j, int k, std::int32_t label,
                                int window) {
  double best2 = INFINITY;
  const auto n = img.dims;
  for (int c = std::max(0, k - window); c <= std::min(n[2] - 1, k + window); ++c)
    for (int b = std::max(0, j - window); b <= std::min(n[1] - 1, j + window); ++b)
      for (int a = std::max(0, i - window); a <= std::min(n[0] - 1, i + window); ++a) {
        if (img.at(a, b, c) == label) continue;
        const double dx = (a - i) * img.spacing[0], dy = (b - j) * img.spacing[1],
                     dz = (c - k) * img.spacing[2];
        best2 = std::min(best2, dx * dx + dy * dy + dz * dz);
      }
  return std::sqrt(best2);
}

}  // namespace tissuemesh::test
