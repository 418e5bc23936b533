// Topological and geometric checks of a multi-material TriSurface (docs/verification.md, "Surface
// validity").
//
// Per tissue (its boundary as TriSurface::tissue_boundary gives it, oriented outward):
//   closed      every edge is used by exactly two of its triangles, once in each direction (so the
//               boundary is also consistently oriented); edges used once are holes, more than twice
//               non-manifold, twice in the same direction misoriented;
//   manifold    (when closed) every vertex's triangles form one fan; a vertex with two or more
//               fans is where the boundary touches itself;
//   intersecting  pairs of its triangles that intersect other than along shared edges/vertices
//               (CGAL Polygon_mesh_processing::self_intersections, exact predicates, or the same
//               rule through a grid, PairSearch; a degenerate triangle, collinear corners, counts
//               as a pair with itself), counted only when the boundary is closed and vertex-manifold;
//   volume      enclosed volume by the divergence theorem, mm^3 (positive when outward).
// Whole complex: triangles stored twice (the same three vertices), and junction polyline edges
// that are not triangle edges where >= 3 triangles meet.
#pragma once

#include "core/tri_surface.h"

#include <cstddef>
#include <string>
#include <vector>

namespace tissuemesh {

struct TissueSurfaceCheck {
  int tissue_id = 0;
  std::string name;
  std::size_t triangles = 0;
  std::size_t vertices = 0;
  std::size_t open_edges = 0;         ///< used by one triangle
  std::size_t nonmanifold_edges = 0;  ///< used by more than two
  std::size_t misoriented_edges = 0;  ///< used twice in the same direction
  std::size_t nonmanifold_vertices = 0;  ///< closed boundary: vertices with more than one fan
  long long intersecting_pairs = -1;  ///< -1 = not checked (not closed, or a non-manifold vertex)
  double volume_mm3 = 0.0;

  bool closed_and_oriented() const { return open_edges == 0 && nonmanifold_edges == 0 && misoriented_edges == 0; }
};

struct SurfaceCheckReport {
  std::vector<TissueSurfaceCheck> tissues;  ///< in tissue id order (1..n)
  std::size_t duplicate_triangles = 0;      ///< triangles whose vertex set occurs before
  std::size_t junction_edges = 0;
  std::size_t junction_edges_off_junction = 0;  ///< junction edges with fewer than 3 triangles

  /// True when every tissue is closed, oriented and intersection free, nothing is stored twice and
  /// every junction edge is a junction of the triangles.
  bool valid() const;
};

/// How check_surface finds intersecting pairs; both give the same pairs and counts.
enum class PairSearch {
  Cgal,  ///< CGAL's self_intersections per tissue boundary: independent of the remesher's own test
  Grid,  ///< surface/intersecting_pairs.h: the same rule, one pass over all triangles on two threads
         ///< (faster on a large surface, e.g. the extraction's)
};

/// When `intersecting` is given, it receives the indices (ascending, unique) of the triangles in an
/// intersecting pair of some tissue's boundary.
SurfaceCheckReport check_surface(const TriSurface& surface, std::vector<int>* intersecting = nullptr,
                                 PairSearch search = PairSearch::Cgal);

/// check_surface(surface, intersecting) after moving points only. `previous` and
/// `previous_intersecting` are the report and the complete intersecting-triangle list (as
/// check_surface or this function returned them, not a subset) of the same triangles before the
/// points listed in `moved` changed; every triangle of `previous_intersecting` must have a moved
/// vertex (else std::invalid_argument; a subset cannot be detected and gives wrong counts). Then
/// only pairs with a triangle touching a moved vertex can have changed, and only those are tested.
/// Same result as check_surface, including the intersecting-pair counts (same rule,
/// surface/triangle_intersection.h).
/// Cost: each tissue triangle inside the box of all changed ones is box-tested against each
/// changed one, so it suits a few scattered moves (the unfolding's tens), not thousands.
SurfaceCheckReport recheck_after_moves(const TriSurface& surface, const SurfaceCheckReport& previous,
                                       const std::vector<int>& previous_intersecting, const std::vector<int>& moved,
                                       std::vector<int>* intersecting = nullptr);

}  // namespace tissuemesh
