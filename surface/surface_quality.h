// Triangle quality of a surface exactly as Table 1 of Alqaoud et al., "Multi-material,
// approach-guided, controlled-resolution breast meshing" reports it.
//
//   average minimal angle  mean over triangles of the smallest of its three angles, degrees
//   minimal angle          smallest angle of any triangle, degrees
//   P30                    percentage of all triangle angles (3 per triangle) below 30 degrees
//   Q_av, Q_min            mean and minimum of the Frey-Borouchaki (1997) shape quality
//                          Q = 6/sqrt(3) * A / (p * h_max): A area, p half-perimeter, h_max longest
//                          edge; 1 for an equilateral triangle, 0 for a degenerate one
// Valette & Chassery (2004) use the same angle figures. Also the edge lengths (mm) for resolution.
#pragma once

#include "core/tri_surface.h"

#include <cstddef>

namespace tissuemesh {

struct SurfaceQuality {
  std::size_t triangles = 0;
  double average_min_angle_deg = 0.0;
  double min_angle_deg = 0.0;
  double p30_percent = 0.0;
  double q_average = 0.0;
  double q_min = 0.0;
  double mean_edge_mm = 0.0;  ///< mean over triangles of their mean edge length
};

/// Quality of all triangles of `surface` (each interface triangle counted once). Zero-area
/// triangles count with angle 0 and Q = 0.
SurfaceQuality surface_quality(const TriSurface& surface);

/// Sharpest fold of `surface`, degrees: the smallest angle between two triangles of one patch (the
/// same region pair) across an edge that only they share, 180 where they are coplanar, 0 where one
/// lies folded flat onto the other. A volume mesher that keeps every surface triangle (TetGen -Y)
/// fills such a wedge with tets no less flat. 180 when there is no such edge.
double sharpest_fold_deg(const TriSurface& surface);

/// True when `after` is no worse than `before` in smallest angle and Q_min, and better in one of
/// them or in P30 (the surface remesher keeps a repair only then, surface/surface_remesh.h).
bool improves_table1_minima(const SurfaceQuality& before, const SurfaceQuality& after);

}  // namespace tissuemesh
