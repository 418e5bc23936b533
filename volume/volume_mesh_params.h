// Parameters of the surface pipeline's volume mesher (config section `volume:`): CGAL Mesh_3
// from the remeshed multi-material surface (volume/complex_mesher.h).
//
// Sizes follow the surface's own size field h(x) = L s(x) (mm; L = the remesher's edge length,
// s = the approach grading, 1 without it), so the volume mesh is as fine as the surface where the
// surface is fine. Meaning of the CGAL criteria: CGAL Mesh_3 manual, "Mesh_criteria_3" (and
// volume/direct_mesh_params.h).
#pragma once

#include "core/yaml_map.h"
#include "volume/mesh3_optimisation.h"

#include <cstddef>
#include <string>

namespace tissuemesh {

struct VolumeMeshParams {
  /// "cgal": CGAL Mesh_3 from the surface complex (complex_mesher.h), which resamples the surface;
  /// "tetgen": TetGen from the surface itself, every surface triangle kept (surface_tetgen.h).
  std::string mesher = "cgal";
  /// Total tets to aim for (0 = none), met within 10 %. With mesher tetgen, cell_edge_factor is
  /// solved (surface_tetgen.h); with mesher cgal, one factor multiplying every size and the facet
  /// distance (complex_mesher.h), the surface then resampled coarser or finer.
  std::size_t target_tets = 0;
  /// Target surface (and junction) edge length relative to h(x): the facet size criterion is the
  /// circumradius of the equilateral triangle of that edge, the feature edge size the edge itself.
  double surface_edge_factor = 1.0;
  /// Largest tet relative to h(x): the cell size criterion is the circumradius of the regular tet
  /// whose edge is cell_edge_factor * e(x), e(x) = min(h(x) + cell_growth * d(x), max_cell_edge_mm).
  /// With mesher tetgen: that circumradius with e = h at the surface points, interpolated inside;
  /// 0 (tetgen only) = no size bound.
  double cell_edge_factor = 1.5;
  /// Interior grading: how fast the tet edge may grow with the distance d(x) (mm) from the nearest
  /// boundary or interface (mm of edge per mm of distance; 0 = no grading: tets as fine as the
  /// surface everywhere). Radius-edge refinement keeps neighbours within a bounded size ratio.
  /// CGAL only (an InputError with mesher tetgen, whose interior follows the surface's sizes).
  double cell_growth = 0.0;
  /// Cap of the graded tet edge e(x), mm; 0 = no cap (the radius-edge bound and the tissue's own
  /// thickness then limit the tets). CGAL only, as cell_growth.
  double max_cell_edge_mm = 0.0;

  /// Edges where a patch folds by more than this (degrees between the normals of its two
  /// triangles) are protected like the junction curves, so creases stay sharp; 180 = junction
  /// curves only (the default: on a coarse remeshed surface many edges fold by more than 60
  /// degrees, and their protecting balls crowd into sub-0.1 mm tets).
  double feature_angle_deg = 180.0;
  double facet_angle_deg = 25.0;        ///< min surface triangle angle, degrees (<= 30 terminates)
  /// Max distance between a surface triangle of the tet mesh and the input surface, mm (times the
  /// size factor under target_tets); 0 = a tenth of the input surface's mean edge length.
  double facet_distance_mm = 0.0;
  double cell_radius_edge_ratio = 2.0;  ///< max tet circumradius / shortest edge (>= 2 terminates)
  Mesh3Optimisation optimise;           ///< optimisation and sliver repair (mesh3_optimisation.h)

  /// Reads the `volume:` map (unknown keys are errors; values range-checked with the key named).
  static VolumeMeshParams from_yaml(YamlMap& map);
  void to_yaml(YAML::Emitter& out) const;
};

}  // namespace tissuemesh
