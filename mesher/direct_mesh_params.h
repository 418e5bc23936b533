// Parameters of the direct pipeline: CGAL Mesh_3 from the labelled image (config section `direct:`).
//
// Sizes are in millimetres (physical, not voxels). Meaning of the CGAL criteria (CGAL Mesh_3
// manual, "Mesh_criteria_3"): facet angle = lower bound on surface triangle angles; facet size =
// upper bound on the radius of surface Delaunay balls; facet distance = upper bound on the distance
// between a surface triangle and the true boundary; cell radius-edge ratio = upper bound on
// circumradius / shortest edge; cell size = upper bound on tet circumradius.
#pragma once

#include "core/yaml_map.h"

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

  bool lloyd = false;                   ///< Lloyd optimisation (slow; off by default)
  bool odt = false;                     ///< ODT optimisation (slow; off by default)
  double optimise_time_limit_s = 10.0;  ///< time limit of each of Lloyd / ODT, s
  /// Sliver perturbation. Off by default: CGAL 5.5's perturber gives a different mesh on every
  /// run (measured), and the same input must give the same output files.
  bool perturb = false;
  bool exude = true;                    ///< sliver exudation
  double sliver_bound_deg = 15.0;       ///< dihedral angle the perturber / exuder aim for, degrees
  double sliver_time_limit_s = 20.0;    ///< time limit of each of perturb / exude, s
  /// Remove tets with a dihedral below this (degrees) that have >= 2 faces on the outer boundary
  /// (flat caps no vertex move can repair; boundary_slivers.h). 0 = keep them.
  double remove_boundary_slivers_deg = 10.0;
  /// Improve tets with a dihedral below this (degrees) by 2-3 flips and edge removals inside one
  /// tissue (sliver_flips.h): interfaces and volumes unchanged. 0 = off.
  double flip_slivers_below_deg = 15.0;
  /// Let those flips give a flat wedge on an interface to the neighbouring tissue (moves the
  /// interface by the wedge's thickness; the moved volume is reported).
  bool interface_flips = true;

  /// Reads the `direct:` map (unknown keys are errors; values range-checked with the key named).
  static DirectMeshParams from_yaml(YamlMap& map);
  void to_yaml(YAML::Emitter& out) const;
};

}  // namespace tissuemesh
