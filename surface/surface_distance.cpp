#include "surface/surface_distance.h"

#include "surface/run_at_once.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <vector>

namespace tissuemesh {
namespace {

/// Margin of the skip test below: far above the rounding of a computed distance (~1e-13 mm on
/// coordinates of ~100 mm), far below any distance reported (printed to 1e-3 mm).
constexpr double kSkipMarginMm = 1e-9;

double max_distance(const TriSurface& from, const SurfaceProjection& to, int threads) {
  // The samples: vertices, triangle centroids and edge midpoints (each edge once). The distance to
  // a surface is 1-Lipschitz, d(p) <= d(v) + |p - v|, so a centroid or midpoint whose bound from
  // its own vertices is under the largest distance found so far cannot raise the maximum and is
  // not queried (most are not). The result is the maximum over all samples.
  // Queries are independent and const: the two halves of each sample list run at once (on
  // `threads` threads, surface/run_at_once.h, which hands an exception back to the caller), each
  // half skipping by its own running maximum; a max is exact, so the result does not depend on the
  // split.
  // [begin, end) of half h (0, 1) of a list of n.
  auto half = [](int h, std::size_t n) { return std::array<std::size_t, 2>{h == 0 ? 0 : n / 2, h == 0 ? n / 2 : n}; };
  auto in_halves = [threads](auto&& part) { run_at_once([&] { part(0); }, [&] { part(1); }, threads); };
  std::vector<double> dv(from.points.size());
  double vertex_max[2] = {0.0, 0.0};
  in_halves([&](int h) {
    const auto [begin, end] = half(h, from.points.size());
    for (std::size_t i = begin; i < end; ++i) vertex_max[h] = std::max(vertex_max[h], dv[i] = to.distance(from.points[i]));
  });
  std::vector<std::array<int, 2>> edges;
  edges.reserve(3 * from.triangles.size());
  for (const std::array<int, 3>& t : from.triangles)
    for (int e = 0; e < 3; ++e) edges.push_back({std::min(t[e], t[(e + 1) % 3]), std::max(t[e], t[(e + 1) % 3])});
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  // A sample at p with corners `ends` (vertex ids): queried unless its bound rules it out.
  auto sample = [&](const Eigen::Vector3d& p, const int* ends, int n, double& best) {
    double bound = INFINITY;
    for (int k = 0; k < n; ++k)
      bound = std::min(bound, dv[static_cast<std::size_t>(ends[k])] + (p - from.points[static_cast<std::size_t>(ends[k])]).norm());
    if (bound > best - kSkipMarginMm) best = std::max(best, to.distance(p));
  };
  // Each half: its half of the triangle centroids, then of the edge midpoints.
  const double d = std::max(vertex_max[0], vertex_max[1]);
  double best[2] = {d, d};
  in_halves([&](int h) {
    const auto [t_begin, t_end] = half(h, from.triangles.size());
    for (std::size_t i = t_begin; i < t_end; ++i) {
      const std::array<int, 3>& t = from.triangles[i];
      sample((from.points[t[0]] + from.points[t[1]] + from.points[t[2]]) / 3.0, t.data(), 3, best[h]);
    }
    const auto [e_begin, e_end] = half(h, edges.size());
    for (std::size_t i = e_begin; i < e_end; ++i)
      sample(0.5 * (from.points[edges[i][0]] + from.points[edges[i][1]]), edges[i].data(), 2, best[h]);
  });
  return std::max(best[0], best[1]);
}

}  // namespace

SurfaceDistance hausdorff_distance(const TriSurface& a, const SurfaceProjection& a_on, const TriSurface& b,
                                   const SurfaceProjection& b_on, int threads) {
  if (threads != 1 && threads != 2) throw std::invalid_argument("hausdorff_distance: threads must be 1 or 2");
  SurfaceDistance d;
  d.a_to_b_mm = max_distance(a, b_on, threads);
  d.b_to_a_mm = max_distance(b, a_on, threads);
  return d;
}

}  // namespace tissuemesh
