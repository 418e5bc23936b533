// Intersecting triangle pairs of a whole multi-material surface, found through a uniform grid of
// triangle boxes (surface/box_grid.h) on two threads: the fast path of check_surface
// (surface/surface_checks.h, PairSearch::Grid) for a large surface such as the extraction's.
//
// The pairs are exactly those CGAL's self_intersections reports on each tissue's boundary: two
// triangles bounding a common tissue, tested by the same rule (surface/triangle_intersection.h,
// exact predicates); a degenerate (collinear) triangle is the pair (t, t) and meets nothing else.
// Each candidate pair is tested once: in the grid cell that holds the lower corner of the overlap
// of the two boxes. Deterministic (the pairs are sorted).
#pragma once

#include "core/tri_surface.h"

#include <array>
#include <vector>

namespace tissuemesh {

/// Pairs (t, u), t <= u, ascending, of triangles of `s` that intersect and both bound a tissue i
/// with checked[i - 1] set (regions are s.labels; 0, outside, is never a tissue). `checked` has one
/// entry per tissue.
std::vector<std::array<int, 2>> intersecting_pairs_by_grid(const TriSurface& s, const std::vector<char>& checked);

}  // namespace tissuemesh
