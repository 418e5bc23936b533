// Exact test whether two triangles of one surface intersect anywhere but in the vertices they share.
//
// The rule is that of CGAL::Polygon_mesh_processing::self_intersections (which the final surface
// check uses), so a remeshing operation the guard lets through never fails that check later:
//   no shared vertex   the closed triangles must be disjoint;
//   one shared vertex  neither triangle's edge opposite the shared vertex may meet the other triangle;
//   a shared edge      the two other vertices must not lie in one plane with the edge on the same
//                      side of it (the triangles would overlap);
//   three shared       the same triangle twice: intersecting.
// Vertices are identified by index (ia, ib); equal indices must carry equal points. Exact
// predicates on the double coordinates (CGAL's filtered Epick kernel).
#pragma once

#include <Eigen/Core>

#include <array>

namespace tissuemesh {

using TrianglePoints = std::array<Eigen::Vector3d, 3>;

/// True when the three corners are collinear (exact). CGAL's self_intersections reports such a
/// triangle as intersecting itself, and only so.
bool triangle_is_degenerate(const TrianglePoints& t);

bool triangles_intersect(const TrianglePoints& a, const std::array<int, 3>& ia, const TrianglePoints& b,
                         const std::array<int, 3>& ib);

/// A triangle with its plane prepared for exact side tests of many points: side(p) is the sign of
/// CGAL::orientation(t[0], t[1], t[2], p), taken from double arithmetic with the normal computed
/// once when Shewchuk's forward error bound for orient3d proves it (and nothing can underflow),
/// else from CGAL's exact predicate; the answer is CGAL's in every case.
class PreparedTriangle {
 public:
  explicit PreparedTriangle(const TrianglePoints& t);
  const TrianglePoints& points() const { return t_; }
  /// +1, -1, or 0 (coplanar), exact.
  int side(const Eigen::Vector3d& p) const;
  /// True when p and q lie strictly on the same side (exact): segment pq misses the plane.
  bool strictly_one_side(const Eigen::Vector3d& p, const Eigen::Vector3d& q) const;

 private:
  TrianglePoints t_;
  Eigen::Vector3d normal_, magnitude_;
  bool filterable_ = false;  ///< edge components far enough from underflow for the double filter
};

/// The same test on prepared triangles (a caller testing one triangle against many prepares it
/// once).
bool triangles_intersect(const PreparedTriangle& a, const std::array<int, 3>& ia, const PreparedTriangle& b,
                         const std::array<int, 3>& ib);

}  // namespace tissuemesh
