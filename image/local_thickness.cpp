#include "image/local_thickness.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace tissuemesh {

namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();

// Felzenszwalb & Huttenlocher's 1D squared distance transform of f sampled at i * step:
// d(i) = min_j (step (i - j))^2 + f(j). v, z, scratch of size n (+1 for z).
void squared_distance_1d(const float* f, float* d, int n, double step, std::vector<int>& v, std::vector<double>& z) {
  int k = 0;
  v[0] = 0;
  z[0] = -std::numeric_limits<double>::infinity();
  z[1] = std::numeric_limits<double>::infinity();
  int first = -1;
  for (int q = 0; q < n; ++q)
    if (f[q] < kInf) {
      first = q;
      break;
    }
  if (first < 0) {
    std::fill(d, d + n, kInf);
    return;
  }
  v[0] = first;
  const double s2 = step * step;
  for (int q = first + 1; q < n; ++q) {
    if (!(f[q] < kInf)) continue;
    // z[0] = -infinity, so the loop stops at k = 0 at the latest.
    auto meet = [&](int p) { return ((f[q] + s2 * q * q) - (f[p] + s2 * p * p)) / (2.0 * s2 * (q - p)); };
    double s = meet(v[k]);
    while (s <= z[k]) s = meet(v[--k]);
    ++k;
    v[k] = q;
    z[k] = s;
    z[k + 1] = std::numeric_limits<double>::infinity();
  }
  k = 0;
  for (int q = 0; q < n; ++q) {
    while (z[k + 1] < q) ++k;
    const double dq = step * (q - v[k]);
    d[q] = static_cast<float>(dq * dq + f[v[k]]);
  }
}

}  // namespace

std::vector<float> local_thickness(const LabelImage& ids, double cap_mm) {
  const auto& dims = ids.dims;
  const std::size_t n = ids.voxel_count();
  const std::size_t stride[3] = {1, static_cast<std::size_t>(dims[0]), static_cast<std::size_t>(dims[0]) * dims[1]};

  // Squared distance (mm^2) to the nearest boundary voxel.
  std::vector<float> e2(n, kInf);
  for (int k = 0; k < dims[2]; ++k)
    for (int j = 0; j < dims[1]; ++j)
      for (int i = 0; i < dims[0]; ++i) {
        const std::size_t v = ids.index(i, j, k);
        const int c[3] = {i, j, k};
        bool boundary = false;
        for (int a = 0; a < 3 && !boundary; ++a) {
          if (c[a] == 0 || c[a] == dims[a] - 1) {
            boundary = true;
            break;
          }
          boundary = ids.labels[v - stride[a]] != ids.labels[v] || ids.labels[v + stride[a]] != ids.labels[v];
        }
        if (boundary) e2[v] = 0.0f;
      }
  {
    const int longest = std::max({dims[0], dims[1], dims[2]});
    std::vector<int> vbuf(longest);
    std::vector<double> zbuf(longest + 1);
    std::vector<float> line(longest), out(longest);
    for (int a = 0; a < 3; ++a) {
      const int a1 = (a + 1) % 3, a2 = (a + 2) % 3;
      for (int u = 0; u < dims[a2]; ++u)
        for (int w = 0; w < dims[a1]; ++w) {
          const std::size_t base = u * stride[a2] + w * stride[a1];
          for (int q = 0; q < dims[a]; ++q) line[q] = e2[base + q * stride[a]];
          squared_distance_1d(line.data(), out.data(), dims[a], ids.spacing[a], vbuf, zbuf);
          for (int q = 0; q < dims[a]; ++q) e2[base + q * stride[a]] = out[q];
        }
    }
  }

  // Paint the balls of the thin ridge voxels.
  const double h = ids.spacing.minCoeff();
  std::vector<float> thickness(n, 0.0f);  // 0: no thin ridge reaches the voxel (yet)
  for (int k = 0; k < dims[2]; ++k)
    for (int j = 0; j < dims[1]; ++j)
      for (int i = 0; i < dims[0]; ++i) {
        const std::size_t v = ids.index(i, j, k);
        const double e = std::sqrt(static_cast<double>(e2[v]));
        const double value = 2.0 * e + h;
        if (value >= cap_mm) continue;
        const std::int32_t label = ids.labels[v];
        bool ridge = true;
        for (int dk = -1; dk <= 1 && ridge; ++dk)
          for (int dj = -1; dj <= 1 && ridge; ++dj)
            for (int di = -1; di <= 1; ++di) {
              const int x = i + di, y = j + dj, z = k + dk;
              if (x < 0 || y < 0 || z < 0 || x >= dims[0] || y >= dims[1] || z >= dims[2]) continue;
              const std::size_t u = ids.index(x, y, z);
              if (ids.labels[u] == label && e2[u] > e2[v]) {
                ridge = false;
                break;
              }
            }
        if (!ridge) continue;
        const double radius = e + 0.5 * h;
        const int r[3] = {static_cast<int>(radius / ids.spacing[0]), static_cast<int>(radius / ids.spacing[1]),
                          static_cast<int>(radius / ids.spacing[2])};
        const float fvalue = static_cast<float>(value);
        for (int z = std::max(0, k - r[2]); z <= std::min(dims[2] - 1, k + r[2]); ++z)
          for (int y = std::max(0, j - r[1]); y <= std::min(dims[1] - 1, j + r[1]); ++y)
            for (int x = std::max(0, i - r[0]); x <= std::min(dims[0] - 1, i + r[0]); ++x) {
              const double dx = (x - i) * ids.spacing[0], dy = (y - j) * ids.spacing[1], dz = (z - k) * ids.spacing[2];
              if (dx * dx + dy * dy + dz * dz > radius * radius) continue;
              const std::size_t u = ids.index(x, y, z);
              if (ids.labels[u] != label) continue;
              thickness[u] = std::max(thickness[u], fvalue);
            }
      }
  for (float& t : thickness)
    if (t == 0.0f) t = kInf;
  return thickness;
}

}  // namespace tissuemesh
