// The manifold pieces of a multi-material surface's patches, as CGAL's polyhedral complex domain
// needs them (volume/complex_mesher.h): one polyhedral surface per piece, each a 2-manifold with
// or without border, consistently oriented.
//
// A piece: triangles of one region pair p|q joined across edges that are not junction edges and
// carry exactly two triangles of that pair (so every piece border lies on a junction curve or on
// a non-manifold edge). A vertex where the piece's triangles form more than one fan (two sheets
// touching at a point) gets one copy per fan, at the same position. Triangles keep their winding
// (normal from p into q). Deterministic: pieces in order of their first triangle.
#pragma once

#include "core/tri_surface.h"

#include <Eigen/Core>

#include <array>
#include <cstddef>
#include <vector>

namespace tissuemesh {

struct SurfacePiece {
  std::array<int, 2> pair{0, 0};                 ///< {p, q} as in TriSurface::labels
  std::vector<Eigen::Vector3d> points;           ///< the piece's own vertices (copies of surface points)
  std::vector<std::array<int, 3>> triangles;     ///< indices into `points`
  std::vector<int> source_triangles;             ///< triangle index in the surface, per triangle
};

struct SurfacePieces {
  std::vector<SurfacePiece> pieces;
  std::size_t duplicated_vertices = 0;  ///< extra copies made for vertices with several fans
};

SurfacePieces manifold_pieces(const TriSurface& surface);

}  // namespace tissuemesh
