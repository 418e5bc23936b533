// SurfaceProjection: closest points on a reference multi-material surface, per patch and per
// junction polyline (the remesher keeps its vertices on the extracted surface with it).
//
// A patch is one region pair (p|q) of the reference TriSurface, numbered in the order the pairs
// first occur in its triangle list (patch_of_triangle()); a curve is one junction polyline. Queries
// return the closest point on that patch's triangles (a grid of triangle boxes, surface/patch_grid.h)
// or that curve's segments (CGAL AABB trees), in double precision, so a projected point lies on
// the reference surface up to round-off and a projected curve point on the reference junction.
// distance() searches the same grid over every patch near the surface and a CGAL AABB tree of
// the whole surface farther away (built once, under std::call_once, at the first such query).
// Build once; queries are const and may run from several threads (CGAL builds a tree's box
// hierarchy lazily, under its own mutex, on its first query).
#pragma once

#include "core/tri_surface.h"

#include <Eigen/Core>

#include <array>
#include <memory>
#include <vector>

namespace tissuemesh {

/// The patch index of every triangle and the region pair of every patch (first-occurrence order).
struct PatchNumbering {
  std::vector<int> patch_of_triangle;
  std::vector<std::array<int, 2>> pair_of_patch;
  /// The patch of region pair p|q (p < q), -1 when the surface has none.
  int patch_of_pair(int p, int q) const;
};
PatchNumbering number_patches(const TriSurface& surface);

class SurfaceProjection {
 public:
  explicit SurfaceProjection(const TriSurface& reference);
  ~SurfaceProjection();
  SurfaceProjection(const SurfaceProjection&) = delete;
  SurfaceProjection& operator=(const SurfaceProjection&) = delete;

  const PatchNumbering& patches() const { return patches_; }
  /// Closest point of patch `patch` / junction `curve` to `p` (mm). `normal`, when given, receives
  /// the unit normal (p -> q) of the patch triangle the point lies on: a caller can tell from it
  /// whether the point landed on the far side of a thin sheet of tissue (both sides one patch).
  Eigen::Vector3d onto_patch(int patch, const Eigen::Vector3d& p, Eigen::Vector3d* normal = nullptr) const;
  Eigen::Vector3d onto_curve(int curve, const Eigen::Vector3d& p) const;
  /// Distance (mm) from p to the closest point of the whole reference surface; std::invalid_argument
  /// for a non-finite p or a surface without triangles.
  double distance(const Eigen::Vector3d& p) const;

 private:
  struct Trees;
  PatchNumbering patches_;
  std::unique_ptr<Trees> trees_;
};

}  // namespace tissuemesh
