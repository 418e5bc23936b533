// Parameters of the direct pipeline: CGAL Mesh_3 from the labelled image (config section `direct:`).
//
// Sizes are in millimetres (physical, not voxels). Meaning of the CGAL criteria (CGAL Mesh_3
// manual, "Mesh_criteria_3"): facet angle = lower bound on surface triangle angles; facet size =
// upper bound on the radius of surface Delaunay balls; facet distance = upper bound on the distance
// between a surface triangle and the true boundary; cell radius-edge ratio = upper bound on
// circumradius / shortest edge; cell size = upper bound on tet circumradius.
#pragma once

#include "core/yaml_map.h"
#include "volume/mesh3_optimisation.h"

#include <map>
#include <string>

namespace tissuemesh {

struct DirectMeshParams {
  double facet_angle_deg = 25.0;        ///< min surface triangle angle, degrees (<= 30 terminates)
  double facet_size_mm = 4.0;           ///< max surface Delaunay ball radius, mm
  double facet_distance_mm = 0.5;       ///< max surface approximation error, mm
  double cell_radius_edge_ratio = 2.0;  ///< max tet circumradius / shortest edge (>= 2 terminates)
  double cell_size_mm = 8.0;            ///< max tet circumradius, mm (default for every tissue)
  std::map<std::string, double> cell_size_per_tissue_mm;  ///< tissue name -> max circumradius, mm

  std::string refine_tissue = "tumor";  ///< tissue the size field refines around ("" = off)
  double refine_size_mm = 1.5;          ///< facet and cell size at that tissue, mm
  double refine_radius_mm = 20.0;       ///< distance over which the size grows back, mm

  bool smooth_boundaries = true;        ///< weighted label interpolation (Stalling et al. 1998)
  /// Gaussian sigma of the weights, mm; 0 = half the largest spacing. Smoothing moves a boundary of
  /// curvature radius R inwards by about sigma^2 / R, so a 15 mm tumour loses ~3% volume at
  /// sigma = 0.75 mm and ~14% at 1.5 mm: keep sigma well below the size of the smallest tissue.
  double smoothing_sigma_mm = 0.0;

  Mesh3Optimisation optimise;           ///< optimisation and sliver repair (mesh3_optimisation.h)

  /// Reads the `direct:` map (unknown keys are errors; values range-checked with the key named).
  static DirectMeshParams from_yaml(YamlMap& map);
  void to_yaml(YAML::Emitter& out) const;
};

}  // namespace tissuemesh
