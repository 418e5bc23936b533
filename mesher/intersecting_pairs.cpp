#include "mesher/intersecting_pairs.h"

#include "mesher/triangle_intersection.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <cstdint>

#include <omp.h>

namespace tissuemesh {
namespace {

/// Grid cell edge over the mean triangle extent (largest box side). A cell then holds ~10-20
/// triangle boxes of a voxel surface and most triangles lie in one or two cells.
constexpr double kCellPerExtent = 2.0;
/// At most this many cells (the cell grows until the surface's box fits; 2^22 as TriangleGrid).
constexpr double kMaxCells = 4194304.0;

/// True when triangles t and u bound a common tissue that is checked.
bool share_checked_tissue(const std::array<int, 2>& a, const std::array<int, 2>& b, const std::vector<char>& checked) {
  for (int p : a)
    if (p > 0 && checked[static_cast<std::size_t>(p - 1)] && (p == b[0] || p == b[1])) return true;
  return false;
}

}  // namespace

std::vector<std::array<int, 2>> intersecting_pairs_by_grid(const TriSurface& s, const std::vector<char>& checked) {
  const int n = static_cast<int>(s.triangles.size());
  std::vector<std::array<int, 2>> pairs;
  if (n == 0) return pairs;
  auto points = [&](int t) {
    const auto& v = s.triangles[static_cast<std::size_t>(t)];
    return TrianglePoints{s.points[static_cast<std::size_t>(v[0])], s.points[static_cast<std::size_t>(v[1])],
                          s.points[static_cast<std::size_t>(v[2])]};
  };
  auto involved = [&](int t) {
    const auto& l = s.labels[static_cast<std::size_t>(t)];
    return (l[0] > 0 && checked[static_cast<std::size_t>(l[0] - 1)]) || (l[1] > 0 && checked[static_cast<std::size_t>(l[1] - 1)]);
  };

  // Boxes of the triangles that bound a checked tissue, and every triangle's prepared plane.
  std::vector<Eigen::AlignedBox3d> box(static_cast<std::size_t>(n));
  std::vector<PreparedTriangle> prepared;
  prepared.reserve(static_cast<std::size_t>(n));
  std::vector<char> use(static_cast<std::size_t>(n), 0);  // bounds a checked tissue, not degenerate
  Eigen::AlignedBox3d all;
  double extent = 0.0;
  for (int t = 0; t < n; ++t) {
    const TrianglePoints p = points(t);
    prepared.emplace_back(p);
    if (!involved(t)) continue;
    box[static_cast<std::size_t>(t)].extend(p[0]).extend(p[1]).extend(p[2]);
    all.extend(box[static_cast<std::size_t>(t)]);
    extent += box[static_cast<std::size_t>(t)].sizes().maxCoeff();
    if (triangle_is_degenerate(p))
      pairs.push_back({t, t});
    else
      use[static_cast<std::size_t>(t)] = 1;
  }
  const auto used = std::count(use.begin(), use.end(), 1);
  if (used < 2) return pairs;

  // The grid: cells of kCellPerExtent mean extents over the used triangles' box, made larger
  // when there would be more than kMaxCells of them.
  double cell = std::max(kCellPerExtent * extent / static_cast<double>(used), 1e-9);
  Eigen::Array3i dims;
  for (;;) {  // in double first: a tiny cell must not overflow int
    const Eigen::Array3d d = ((all.max() - all.min()).array() / cell).floor() + 1.0;
    if (d.prod() <= kMaxCells) {
      dims = d.cast<int>();
      break;
    }
    cell *= 1.25;
  }
  auto cell_of = [&](const Eigen::Vector3d& p) {
    Eigen::Array3i c = ((p - all.min()).array() / cell).floor().cast<int>();
    return c.max(0).min(dims - 1).eval();
  };
  auto index = [&](const Eigen::Array3i& c) {
    return (static_cast<std::int64_t>(c[2]) * dims[1] + c[1]) * dims[0] + c[0];
  };
  const std::size_t cells = static_cast<std::size_t>(dims[0]) * dims[1] * dims[2];
  // Cell lists as one array (counting sort), each list in ascending triangle order.
  std::vector<std::int64_t> start(cells + 1, 0);
  auto for_cells = [&](int t, auto f) {
    const Eigen::Array3i lo = cell_of(box[static_cast<std::size_t>(t)].min()), hi = cell_of(box[static_cast<std::size_t>(t)].max());
    for (int k = lo[2]; k <= hi[2]; ++k)
      for (int j = lo[1]; j <= hi[1]; ++j)
        for (int i = lo[0]; i <= hi[0]; ++i) f(index(Eigen::Array3i(i, j, k)));
  };
  for (int t = 0; t < n; ++t)
    if (use[static_cast<std::size_t>(t)]) for_cells(t, [&](std::int64_t c) { ++start[static_cast<std::size_t>(c) + 1]; });
  for (std::size_t c = 0; c < cells; ++c) start[c + 1] += start[c];
  std::vector<int> list(static_cast<std::size_t>(start[cells]));
  std::vector<std::int64_t> fill(start.begin(), start.end() - 1);
  for (int t = 0; t < n; ++t)
    if (use[static_cast<std::size_t>(t)]) for_cells(t, [&](std::int64_t c) { list[static_cast<std::size_t>(fill[static_cast<std::size_t>(c)]++)] = t; });

  // Every pair of boxes that overlap meets in the cell of the overlap's lower corner: tested there.
  std::vector<std::vector<std::array<int, 2>>> found(2);
  const std::int64_t count = static_cast<std::int64_t>(cells);
#pragma omp parallel for schedule(dynamic, 4096) num_threads(2)
  for (std::int64_t c = 0; c < count; ++c) {
    std::vector<std::array<int, 2>>& out = found[omp_get_thread_num() == 0 ? 0 : 1];
    for (std::int64_t i = start[c]; i < start[c + 1]; ++i) {
      const int t = list[static_cast<std::size_t>(i)];
      const Eigen::AlignedBox3d& bt = box[static_cast<std::size_t>(t)];
      for (std::int64_t j = i + 1; j < start[c + 1]; ++j) {
        const int u = list[static_cast<std::size_t>(j)];
        const Eigen::AlignedBox3d& bu = box[static_cast<std::size_t>(u)];
        if (!bt.intersects(bu) || index(cell_of(bt.min().cwiseMax(bu.min()))) != c) continue;
        if (!share_checked_tissue(s.labels[static_cast<std::size_t>(t)], s.labels[static_cast<std::size_t>(u)], checked)) continue;
        if (triangles_intersect(prepared[static_cast<std::size_t>(t)], s.triangles[static_cast<std::size_t>(t)],
                                prepared[static_cast<std::size_t>(u)], s.triangles[static_cast<std::size_t>(u)]))
          out.push_back({t, u});
      }
    }
  }
  for (const auto& f : found) pairs.insert(pairs.end(), f.begin(), f.end());
  std::sort(pairs.begin(), pairs.end());
  return pairs;
}

}  // namespace tissuemesh
