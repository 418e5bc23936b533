#include "surface/surface_projection.h"

#include "core/errors.h"
#include "surface/patch_grid.h"
#include "surface/run_at_once.h"

#include <CGAL/AABB_segment_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Simple_cartesian.h>

#include <algorithm>
#include <map>
#include <mutex>
#include <stdexcept>
#include <string>
#include <utility>

namespace tissuemesh {
namespace {

using K = CGAL::Simple_cartesian<double>;
using Point = K::Point_3;
using Triangle = K::Triangle_3;
using Segment = K::Segment_3;
using TriangleTree =
    CGAL::AABB_tree<CGAL::AABB_traits<K, CGAL::AABB_triangle_primitive<K, std::vector<Triangle>::const_iterator>>>;
using SegmentTree =
    CGAL::AABB_tree<CGAL::AABB_traits<K, CGAL::AABB_segment_primitive<K, std::vector<Segment>::const_iterator>>>;

/// Shells of patch-grid cells distance() searches before it asks the box tree (a cube of 5^3
/// cells of twice the mean triangle size).
constexpr int kGridShells = 2;

Point point(const Eigen::Vector3d& p) { return Point(p.x(), p.y(), p.z()); }
Eigen::Vector3d vector(const Point& p) { return Eigen::Vector3d(p.x(), p.y(), p.z()); }

}  // namespace

PatchNumbering number_patches(const TriSurface& surface) {
  PatchNumbering n;
  std::map<std::array<int, 2>, int> index;
  n.patch_of_triangle.reserve(surface.triangles.size());
  for (const std::array<int, 2>& pq : surface.labels) {
    auto it = index.emplace(pq, static_cast<int>(n.pair_of_patch.size())).first;
    if (it->second == static_cast<int>(n.pair_of_patch.size())) n.pair_of_patch.push_back(pq);
    n.patch_of_triangle.push_back(it->second);
  }
  return n;
}

int PatchNumbering::patch_of_pair(int p, int q) const {
  const auto it = std::find(pair_of_patch.begin(), pair_of_patch.end(), std::array<int, 2>{p, q});
  return it == pair_of_patch.end() ? -1 : static_cast<int>(it - pair_of_patch.begin());
}

struct SurfaceProjection::Trees {
  std::vector<std::vector<Segment>> curve_segments;
  std::vector<Triangle> all_triangles;
  std::unique_ptr<PatchGrid> patches;
  std::vector<std::unique_ptr<SegmentTree>> curve;
  std::unique_ptr<TriangleTree> all;  ///< built by the first distance() query far from the surface
  std::once_flag all_built;
};

SurfaceProjection::SurfaceProjection(const TriSurface& reference)
    : patches_(number_patches(reference)), trees_(std::make_unique<Trees>()) {
  Trees& t = *trees_;
  t.all_triangles.reserve(reference.triangles.size());
  std::vector<std::array<Eigen::Vector3d, 3>> corners;
  corners.reserve(reference.triangles.size());
  for (const std::array<int, 3>& v : reference.triangles) {
    corners.push_back({reference.points[v[0]], reference.points[v[1]], reference.points[v[2]]});
    t.all_triangles.emplace_back(point(reference.points[v[0]]), point(reference.points[v[1]]), point(reference.points[v[2]]));
  }
  t.curve_segments.resize(reference.junctions.size());
  for (std::size_t c = 0; c < reference.junctions.size(); ++c) {
    const std::vector<int>& line = reference.junctions[c];
    for (std::size_t i = 0; i + 1 < line.size(); ++i)
      t.curve_segments[c].emplace_back(point(reference.points[line[i]]), point(reference.points[line[i + 1]]));
  }
  // The patch grid and the curve trees share nothing: built on two threads (each is the same
  // whichever thread builds it).
  run_at_once([&] { t.patches = std::make_unique<PatchGrid>(std::move(corners), patches_.patch_of_triangle); },
              [&] {
                for (const std::vector<Segment>& segments : t.curve_segments) {
                  t.curve.push_back(std::make_unique<SegmentTree>(segments.begin(), segments.end()));
                  t.curve.back()->accelerate_distance_queries();
                }
              });
}

SurfaceProjection::~SurfaceProjection() = default;

Eigen::Vector3d SurfaceProjection::onto_patch(int patch, const Eigen::Vector3d& p, Eigen::Vector3d* normal) const {
  if (patch < 0 || patch >= static_cast<int>(patches_.pair_of_patch.size()))
    throw std::out_of_range("SurfaceProjection::onto_patch: no patch " + std::to_string(patch));
  const PatchGrid::Hit hit = trees_->patches->closest(patch, p);
  if (hit.triangle < 0)
    throw std::invalid_argument("SurfaceProjection::onto_patch: no closest point on patch " + std::to_string(patch) +
                                " (a non-finite query point)");
  if (normal) {
    const Triangle& t = trees_->all_triangles[static_cast<std::size_t>(hit.triangle)];
    *normal = (vector(t[1]) - vector(t[0])).cross(vector(t[2]) - vector(t[0])).normalized();
  }
  return hit.point;
}

Eigen::Vector3d SurfaceProjection::onto_curve(int curve, const Eigen::Vector3d& p) const {
  return vector(trees_->curve.at(curve)->closest_point(point(p)));
}

double SurfaceProjection::distance(const Eigen::Vector3d& p) const {
  if (!p.allFinite()) throw std::invalid_argument("SurfaceProjection::distance: a non-finite query point");
  if (trees_->all_triangles.empty()) throw std::invalid_argument("SurfaceProjection::distance: the surface has no triangles");
  // Near the surface (the Hausdorff samples, most points a size field asks about) the patch grid
  // finds the closest point in a few cells; far from it, where the grid would search cubes of
  // cells growing with the distance, the whole surface's box tree (a logarithmic search).
  Trees& t = *trees_;
  const PatchGrid::Hit hit = t.patches->closest_any(p, kGridShells);
  if (hit.triangle >= 0) return (hit.point - p).norm();
  std::call_once(t.all_built, [&t] {
    t.all = std::make_unique<TriangleTree>(t.all_triangles.begin(), t.all_triangles.end());
    t.all->accelerate_distance_queries();
  });
  return std::sqrt(t.all->squared_distance(point(p)));
}

}  // namespace tissuemesh
