// Why reimplemented: CGAL's generate_label_weights needs ITK, which is not a dependency we want.
#include "volume/label_weights.h"

#include <algorithm>
#include <cmath>
#include <set>

namespace tissuemesh {

namespace {

std::vector<float> gaussian_kernel(double sigma_vox) {
  const int r = std::max(1, static_cast<int>(std::ceil(3.0 * sigma_vox)));
  std::vector<float> k(2 * r + 1);
  double sum = 0.0;
  for (int i = -r; i <= r; ++i) sum += k[i + r] = static_cast<float>(std::exp(-0.5 * i * i / (sigma_vox * sigma_vox)));
  for (auto& v : k) v = static_cast<float>(v / sum);
  return k;
}

// Convolves `data` along one axis inside the box [lo, hi] (inclusive); samples beyond the image
// border repeat the border value (the label continues past the border as far as we know).
void convolve_axis(std::vector<float>& data, const std::array<int, 3>& dims, int axis,
                   const std::vector<float>& kernel, const std::array<int, 3>& lo,
                   const std::array<int, 3>& hi) {
  const int r = static_cast<int>(kernel.size() / 2);
  const std::size_t stride[3] = {1, static_cast<std::size_t>(dims[0]),
                                 static_cast<std::size_t>(dims[0]) * dims[1]};
  const int a1 = (axis + 1) % 3, a2 = (axis + 2) % 3;
  std::vector<float> line(dims[axis]), out(dims[axis]);
  for (int u = lo[a2]; u <= hi[a2]; ++u) {
    for (int w = lo[a1]; w <= hi[a1]; ++w) {
      const std::size_t base = u * stride[a2] + w * stride[a1];
      for (int i = 0; i < dims[axis]; ++i) line[i] = data[base + i * stride[axis]];
      for (int i = lo[axis]; i <= hi[axis]; ++i) {
        float s = 0.0f;
        for (int t = -r; t <= r; ++t) {
          const int j = std::clamp(i + t, 0, dims[axis] - 1);
          s += kernel[t + r] * line[j];
        }
        out[i] = s;
      }
      for (int i = lo[axis]; i <= hi[axis]; ++i) data[base + i * stride[axis]] = out[i];
    }
  }
}

}  // namespace

std::vector<std::uint8_t> label_weights(const LabelImage& ids, double sigma_mm) {
  const auto& d = ids.dims;
  std::vector<std::uint8_t> weights(ids.voxel_count(), 0);
  std::vector<float> best(ids.voxel_count(), 0.0f);
  std::set<std::int32_t> labels(ids.labels.begin(), ids.labels.end());
  std::vector<float> ind(ids.voxel_count());
  for (std::int32_t label : labels) {
    // Smooth only inside the label's bounding box grown by the kernel radius: small tissues
    // (tumor, islands) then cost little.
    std::array<int, 3> lo = d, hi = {-1, -1, -1};
    for (int k = 0; k < d[2]; ++k)
      for (int j = 0; j < d[1]; ++j)
        for (int i = 0; i < d[0]; ++i) {
          const bool in = ids.at(i, j, k) == label;
          ind[ids.index(i, j, k)] = in ? 1.0f : 0.0f;
          if (in) {
            lo = {std::min(lo[0], i), std::min(lo[1], j), std::min(lo[2], k)};
            hi = {std::max(hi[0], i), std::max(hi[1], j), std::max(hi[2], k)};
          }
        }
    std::array<std::vector<float>, 3> kernels;
    for (int a = 0; a < 3; ++a) {
      kernels[a] = gaussian_kernel(sigma_mm / ids.spacing[a]);
      const int r = static_cast<int>(kernels[a].size() / 2);
      lo[a] = std::max(0, lo[a] - r);
      hi[a] = std::min(d[a] - 1, hi[a] + r);
    }
    for (int a = 0; a < 3; ++a) convolve_axis(ind, d, a, kernels[a], lo, hi);
    for (int k = lo[2]; k <= hi[2]; ++k)
      for (int j = lo[1]; j <= hi[1]; ++j)
        for (int i = lo[0]; i <= hi[0]; ++i) {
          const std::size_t v = ids.index(i, j, k);
          best[v] = std::max(best[v], ind[v]);
        }
  }
  // Floor: CGAL treats weights below 128 as 128, where a voxel's own label only just beats its
  // neighbours' at the voxel centre. Such a voxel (a thin strand, a three-label corner) then owns
  // a region a hundredth of a voxel wide, and Delaunay refinement piles up near-degenerate tets
  // resolving it. With weights >= kMinWeight every voxel keeps a region about a third of a voxel
  // across (the crossing of w -> 255 - w_neighbour and 255 - w -> w_neighbour), like the
  // unweighted labelling, while smooth parts of boundaries keep the smoothing.
  constexpr float kMinWeight = 170.0f / 255.0f;
  for (std::size_t v = 0; v < best.size(); ++v)
    weights[v] = static_cast<std::uint8_t>(std::lround(std::clamp(best[v], kMinWeight, 1.0f) * 255.0f));
  return weights;
}

}  // namespace tissuemesh
