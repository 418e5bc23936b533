// Distance between two triangle surfaces (e.g. the remeshed surface against the extracted one).
#pragma once

#include "core/tri_surface.h"
#include "surface/surface_projection.h"

namespace tissuemesh {

struct SurfaceDistance {
  double a_to_b_mm = 0.0;  ///< max over samples of `a` of the distance to `b`
  double b_to_a_mm = 0.0;  ///< max over samples of `b` of the distance to `a`
  double symmetric_mm() const { return a_to_b_mm > b_to_a_mm ? a_to_b_mm : b_to_a_mm; }
};

/// Symmetric Hausdorff distance, sampled: every vertex, edge midpoint and triangle centroid of each
/// surface against the other's triangles (exact closest points). `a_on`/`b_on` are projections
/// built on `a`/`b`. Sampling bounds the true value from below; with these samples the gap is at
/// most the deviation of a triangle's interior between samples, well under its edge length.
/// `threads` (1 or 2, else std::invalid_argument) share the queries; the result does not depend
/// on it (1 beside other work on a two-core machine).
SurfaceDistance hausdorff_distance(const TriSurface& a, const SurfaceProjection& a_on, const TriSurface& b,
                                   const SurfaceProjection& b_on, int threads = 2);

}  // namespace tissuemesh
