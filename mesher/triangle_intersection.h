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

}  // namespace tissuemesh
