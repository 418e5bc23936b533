// Why: CGAL's self_intersections, run per tissue boundary, tests every triangle once per tissue it
// bounds (an interface triangle twice); one pass over the whole surface tests each pair once.
#include "surface/intersecting_pairs.h"

#include "surface/box_grid.h"
#include "surface/triangle_intersection.h"

#include <algorithm>
#include <cstdint>

#include <omp.h>

namespace tissuemesh {
namespace {

/// Grid cell edge over the mean triangle extent (largest box side). A cell then holds ~10-20
/// triangle boxes of a voxel surface and most triangles lie in one or two cells.
constexpr double kCellPerExtent = 2.0;

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
  std::vector<Eigen::Vector3d> lo(static_cast<std::size_t>(n)), hi(static_cast<std::size_t>(n));
  std::vector<PreparedTriangle> prepared;
  prepared.reserve(static_cast<std::size_t>(n));
  std::vector<char> use(static_cast<std::size_t>(n), 0);  // bounds a checked tissue, not degenerate
  for (int t = 0; t < n; ++t) {
    const TrianglePoints p = points(t);
    prepared.emplace_back(p);
    if (!involved(t)) continue;
    lo[static_cast<std::size_t>(t)] = p[0].cwiseMin(p[1]).cwiseMin(p[2]);
    hi[static_cast<std::size_t>(t)] = p[0].cwiseMax(p[1]).cwiseMax(p[2]);
    if (triangle_is_degenerate(p))
      pairs.push_back({t, t});
    else
      use[static_cast<std::size_t>(t)] = 1;
  }
  if (std::count(use.begin(), use.end(), 1) < 2) return pairs;
  const BoxGrid grid(lo, hi, use, kCellPerExtent);

  // Every pair of boxes that overlap meets in the cell of the overlap's lower corner: tested there.
  std::vector<std::vector<std::array<int, 2>>> found(2);
  const std::int64_t cells = grid.cells();
#pragma omp parallel for schedule(dynamic, 4096) num_threads(2)
  for (std::int64_t c = 0; c < cells; ++c) {
    std::vector<std::array<int, 2>>& out = found[omp_get_thread_num() == 0 ? 0 : 1];
    for (const int* i = grid.begin(c); i != grid.end(c); ++i) {
      const auto t = static_cast<std::size_t>(*i);
      for (const int* j = i + 1; j != grid.end(c); ++j) {
        const auto u = static_cast<std::size_t>(*j);
        const bool overlap = (lo[t].array() <= hi[u].array()).all() && (lo[u].array() <= hi[t].array()).all();
        if (!overlap || grid.index(grid.cell_of(lo[t].cwiseMax(lo[u]))) != c) continue;
        if (!share_checked_tissue(s.labels[t], s.labels[u], checked)) continue;
        if (triangles_intersect(prepared[t], s.triangles[t], prepared[u], s.triangles[u])) out.push_back({*i, *j});
      }
    }
  }
  for (const auto& f : found) pairs.insert(pairs.end(), f.begin(), f.end());
  std::sort(pairs.begin(), pairs.end());
  return pairs;
}

}  // namespace tissuemesh
