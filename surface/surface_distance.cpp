#include "surface/surface_distance.h"

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
  // Queries are independent and const: `threads` threads; a max is exact, so the result does not
  // depend on the split.
  const auto nv = static_cast<std::ptrdiff_t>(from.points.size());
  std::vector<double> dv(from.points.size());
  double d = 0.0;
#pragma omp parallel for schedule(static) num_threads(threads) reduction(max : d)
  for (std::ptrdiff_t i = 0; i < nv; ++i) {
    dv[static_cast<std::size_t>(i)] = to.distance(from.points[static_cast<std::size_t>(i)]);
    d = std::max(d, dv[static_cast<std::size_t>(i)]);
  }
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
  const auto nt = static_cast<std::ptrdiff_t>(from.triangles.size());
  const auto ne = static_cast<std::ptrdiff_t>(edges.size());
  const double vertex_max = d;
#pragma omp parallel num_threads(threads) reduction(max : d)
  {
    double best = vertex_max;
#pragma omp for schedule(static) nowait
    for (std::ptrdiff_t i = 0; i < nt; ++i) {
      const std::array<int, 3>& t = from.triangles[static_cast<std::size_t>(i)];
      sample((from.points[t[0]] + from.points[t[1]] + from.points[t[2]]) / 3.0, t.data(), 3, best);
    }
#pragma omp for schedule(static)
    for (std::ptrdiff_t i = 0; i < ne; ++i) {
      const std::array<int, 2>& e = edges[static_cast<std::size_t>(i)];
      sample(0.5 * (from.points[e[0]] + from.points[e[1]]), e.data(), 2, best);
    }
    d = std::max(d, best);
  }
  return d;
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
