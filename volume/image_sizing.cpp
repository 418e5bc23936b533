// Why blocks: the field is graded and summed a dozen times while the budget is solved, and
// CGAL evaluates it millions of times; a grid of at most ~2 M blocks keeps both cheap on images of
// tens of millions of voxels, and the smallest value per block keeps thin parts resolved.
// Why a constant tet volume factor: Delaunay refinement to a circumradius bound gives tets of a
// stable mean shape, so the count follows the integral of 1 / edge^3 up to that factor; the
// mesher measures it on its own result and corrects.
#include "volume/image_sizing.h"

#include "core/errors.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

namespace tissuemesh {

namespace {

constexpr std::size_t kMaxBlocks = 2000000;

// Chamfer grading: l(v) = min over u of l(u) + growth * |u - v| on the block grid, two raster
// passes over the 26 neighbours (within 8 % of the Euclidean distance).
void grade(std::vector<float>& l, const std::array<int, 3>& n, const Eigen::Vector3d& step, double growth) {
  struct Offset {
    int di, dj, dk;
    float cost;
  };
  std::vector<Offset> back;  // neighbours before (i, j, k) in raster order
  for (int dk = -1; dk <= 0; ++dk)
    for (int dj = -1; dj <= 1; ++dj)
      for (int di = -1; di <= 1; ++di) {
        if (dk == 0 && (dj > 0 || (dj == 0 && di >= 0))) continue;
        const double d = std::sqrt(std::pow(di * step[0], 2) + std::pow(dj * step[1], 2) + std::pow(dk * step[2], 2));
        back.push_back({di, dj, dk, static_cast<float>(growth * d)});
      }
  auto at = [&](int i, int j, int k) -> float& {
    return l[static_cast<std::size_t>(i) + static_cast<std::size_t>(n[0]) * (j + static_cast<std::size_t>(n[1]) * k)];
  };
  auto relax = [&](int i, int j, int k, int sign) {
    float& v = at(i, j, k);
    for (const Offset& o : back) {
      const int x = i + sign * o.di, y = j + sign * o.dj, z = k + sign * o.dk;
      if (x < 0 || y < 0 || z < 0 || x >= n[0] || y >= n[1] || z >= n[2]) continue;
      v = std::min(v, at(x, y, z) + o.cost);
    }
  };
  for (int k = 0; k < n[2]; ++k)
    for (int j = 0; j < n[1]; ++j)
      for (int i = 0; i < n[0]; ++i) relax(i, j, k, 1);
  for (int k = n[2] - 1; k >= 0; --k)
    for (int j = n[1] - 1; j >= 0; --j)
      for (int i = n[0] - 1; i >= 0; --i) relax(i, j, k, -1);
}

}  // namespace

double ImageSizing::edge_at(double x, double y, double z) const {
  const double p[3] = {x / spacing[0], y / spacing[1], z / spacing[2]};
  int lo[3], hi[3];
  for (int a = 0; a < 3; ++a) {
    const int last = blocks[a] * block - 1;
    lo[a] = std::clamp(static_cast<int>(std::floor(p[a])), 0, last) / block;
    hi[a] = std::clamp(static_cast<int>(std::ceil(p[a])), 0, last) / block;
    lo[a] = std::min(lo[a], blocks[a] - 1);
    hi[a] = std::min(hi[a], blocks[a] - 1);
  }
  float best = std::numeric_limits<float>::infinity();
  for (int k = lo[2]; k <= hi[2]; ++k)
    for (int j = lo[1]; j <= hi[1]; ++j)
      for (int i = lo[0]; i <= hi[0]; ++i)
        best = std::min(best, graded[static_cast<std::size_t>(i) +
                                     static_cast<std::size_t>(blocks[0]) * (j + static_cast<std::size_t>(blocks[1]) * k)]);
  return std::clamp<double>(best, min_edge_mm, global_edge_mm);
}

double ImageSizing::predict(double s, double tet_volume_factor) const {
  const double voxel = spacing.prod();
  double sum = 0.0;
  for (std::size_t b = 0; b < graded.size(); ++b) {
    if (tissue_voxels[b] == 0) continue;
    const double e = std::clamp<double>(graded[b], min_edge_mm, s);
    sum += tissue_voxels[b] * voxel / (tet_volume_factor * e * e * e);
  }
  return sum;
}

double ImageSizing::solve(double target, double tet_volume_factor, double max_edge_mm) const {
  double lo = min_edge_mm, hi = max_edge_mm;
  if (predict(hi, tet_volume_factor) >= target) return hi;
  if (predict(lo, tet_volume_factor) <= target) return lo;
  for (int it = 0; it < 60; ++it) {  // predict falls as s grows
    const double mid = std::sqrt(lo * hi);
    (predict(mid, tet_volume_factor) > target ? lo : hi) = mid;
  }
  return std::sqrt(lo * hi);
}

ImageSizing size_from_image(const LabelImage& ids, const std::vector<float>& thickness,
                            const std::function<double(int, int, int)>& cap, const std::vector<std::string>& names,
                            const ImageSizingParams& p) {
  if (p.target_tets == 0) throw InputError("direct.target_tets: the budget must be a positive number of tets");
  if (!(p.thickness_edge_ratio > 0) || !(p.growth > 0) || !(p.min_edge_mm > 0) || !(p.max_edge_mm >= p.min_edge_mm) ||
      !(p.tet_volume_factor > 0))
    throw InputError("direct: image sizing needs thickness_edge_ratio, size_growth, a minimum edge > 0 and a maximum "
                     "edge >= the minimum");
  ImageSizing s;
  s.spacing = ids.spacing;
  s.min_edge_mm = p.min_edge_mm;
  const std::size_t voxels = ids.voxel_count();
  while (static_cast<std::size_t>(s.block) * s.block * s.block * kMaxBlocks < voxels) ++s.block;
  for (int a = 0; a < 3; ++a) s.blocks[a] = (ids.dims[a] + s.block - 1) / s.block;
  const std::size_t nb = static_cast<std::size_t>(s.blocks[0]) * s.blocks[1] * s.blocks[2];
  std::vector<float> base(nb, std::numeric_limits<float>::infinity());
  s.tissue_voxels.assign(nb, 0);
  auto block_of = [&](int i, int j, int k) {
    return static_cast<std::size_t>(i / s.block) +
           static_cast<std::size_t>(s.blocks[0]) * (j / s.block + static_cast<std::size_t>(s.blocks[1]) * (k / s.block));
  };
  for (int k = 0; k < ids.dims[2]; ++k)
    for (int j = 0; j < ids.dims[1]; ++j)
      for (int i = 0; i < ids.dims[0]; ++i) {
        const std::size_t v = ids.index(i, j, k), b = block_of(i, j, k);
        const double want = std::min<double>(p.thickness_edge_ratio * thickness[v], cap(i, j, k));
        base[b] = std::min(base[b], static_cast<float>(want));
        if (ids.labels[v] != 0) ++s.tissue_voxels[b];
      }
  const Eigen::Vector3d step = ids.spacing * s.block;
  auto graded_with = [&](double beta) {
    std::vector<float> l(nb);
    for (std::size_t b = 0; b < nb; ++b)
      l[b] = static_cast<float>(std::min<double>(beta * base[b], std::numeric_limits<float>::max()));
    grade(l, s.blocks, step, p.growth);
    return l;
  };
  const double target = static_cast<double>(p.target_tets);
  s.graded = graded_with(1.0);
  if (s.predict(p.max_edge_mm, p.tet_volume_factor) > target) {
    // The thin parts alone exceed the budget: coarsen them all by one factor.
    double lo = 1.0, hi = 2.0;
    while (hi < 1e4) {
      s.graded = graded_with(hi);
      if (s.predict(p.max_edge_mm, p.tet_volume_factor) <= target) break;
      lo = hi;
      hi *= 2.0;
    }
    for (int it = 0; it < 12; ++it) {
      const double mid = std::sqrt(lo * hi);
      s.graded = graded_with(mid);
      (s.predict(p.max_edge_mm, p.tet_volume_factor) > target ? lo : hi) = mid;
    }
    s.thickness_scale = hi;
    s.graded = graded_with(hi);
  }
  s.global_edge_mm = s.solve(target, p.tet_volume_factor, p.max_edge_mm);
  s.predicted_tets = s.predict(s.global_edge_mm, p.tet_volume_factor);

  // Thin voxels whose edge is coarser than their thickness asks for.
  std::map<int, double> thin;
  for (int k = 0; k < ids.dims[2]; ++k)
    for (int j = 0; j < ids.dims[1]; ++j)
      for (int i = 0; i < ids.dims[0]; ++i) {
        const std::size_t v = ids.index(i, j, k);
        const int id = ids.labels[v];
        if (id == 0 || !std::isfinite(thickness[v])) continue;
        const double e = std::clamp<double>(s.graded[block_of(i, j, k)], s.min_edge_mm, s.global_edge_mm);
        if (e > 1.01 * p.thickness_edge_ratio * thickness[v]) thin[id] += ids.voxel_volume();
      }
  for (const auto& [id, volume] : thin)
    if (id >= 1 && static_cast<std::size_t>(id) <= names.size()) s.coarsened.push_back({names[id - 1], volume});
  return s;
}

}  // namespace tissuemesh
