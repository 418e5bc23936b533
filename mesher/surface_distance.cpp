#include "mesher/surface_distance.h"

#include <algorithm>
#include <array>
#include <vector>

namespace tissuemesh {
namespace {

double max_distance(const TriSurface& from, const SurfaceProjection& to) {
  // The samples: vertices, triangle centroids and edge midpoints (each edge once).
  std::vector<Eigen::Vector3d> samples(from.points);
  std::vector<std::array<int, 2>> edges;
  edges.reserve(3 * from.triangles.size());
  for (const std::array<int, 3>& t : from.triangles) {
    const Eigen::Vector3d &a = from.points[t[0]], &b = from.points[t[1]], &c = from.points[t[2]];
    samples.push_back((a + b + c) / 3.0);
    for (int e = 0; e < 3; ++e) edges.push_back({std::min(t[e], t[(e + 1) % 3]), std::max(t[e], t[(e + 1) % 3])});
  }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  for (const auto& [a, b] : edges) samples.push_back(0.5 * (from.points[a] + from.points[b]));
  // Queries are independent (the projection's trees are built in its constructor): two threads;
  // a max is exact, so the result does not depend on the split.
  double d = samples.empty() ? 0.0 : to.distance(samples.front());
  const auto n = static_cast<std::ptrdiff_t>(samples.size());
#pragma omp parallel for schedule(static) num_threads(2) reduction(max : d)
  for (std::ptrdiff_t i = 0; i < n; ++i) d = std::max(d, to.distance(samples[static_cast<std::size_t>(i)]));
  return d;
}

}  // namespace

SurfaceDistance hausdorff_distance(const TriSurface& a, const SurfaceProjection& a_on, const TriSurface& b,
                                   const SurfaceProjection& b_on) {
  SurfaceDistance d;
  d.a_to_b_mm = max_distance(a, b_on);
  d.b_to_a_mm = max_distance(b, a_on);
  return d;
}

}  // namespace tissuemesh
