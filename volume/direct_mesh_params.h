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

#include <cstddef>
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

  /// Tissue components (6-connected) below either threshold join the region around them before
  /// meshing (image/small_islands.h) and are reported by tissue, count and volume. Both 0 keep
  /// every component. The default 0.25 mm^3 (16 voxels at 0.25 mm spacing, 2 at 0.5 mm, none at
  /// the phantom's 0.7 x 0.7 x 1.5 mm) is a speck a few tets across even at a facet distance of
  /// half a voxel: its meshed volume is off by about its own, while each one kept is a closed
  /// surface that refinement resolves to the full criteria and grades the mesh around. Specks of
  /// two tissues inside each other trade volume, so the net change per tissue stays small.
  int min_component_voxels = 0;         ///< fewer voxels than this: absorbed (0 = off)
  double min_component_mm3 = 0.25;      ///< smaller volume than this, mm^3: absorbed (0 = off)

  /// Element budget: > 0 derives the sizes from the image (each tissue's local thickness, graded
  /// away from thin parts, docs/direct-pipeline.md "Sizes from the image") so that the mesh has
  /// about this many tets; facet_size_mm, cell_size_mm, cell_size_per_tissue_mm and refine_* are
  /// then upper bounds. 0 = the fixed sizes above.
  std::size_t target_tets = 0;
  double thickness_edge_ratio = 1.0;    ///< with target_tets: edge length / local thickness
  double size_growth = 0.3;             ///< with target_tets: edge growth per mm away from thin parts
  /// with target_tets: facet distance / local edge (facet_distance_mm is then an upper bound)
  double facet_distance_ratio = 0.05;
  double min_edge_mm = 0.0;             ///< with target_tets: smallest edge, mm; 0 = smallest voxel spacing

  /// Enclosed components of at most this voxel volume (mm^3) are scaled to it after meshing
  /// (component_volume_fit.h): a blob a few elements across is otherwise meshed tens of percent
  /// too small. 0 = off.
  double fit_island_volumes_below_mm3 = 100.0;

  /// Last, the mesh's boundary and interface nodes move by patch offsets so that every tissue's
  /// tets fill its voxel volume (tet_volume_restoration.h): chords of a curved boundary, label
  /// smoothing, coarse elements and the half voxels beyond the border voxels' centres otherwise
  /// take a few per cent off a tissue. Each node moves at most one voxel (the largest spacing) in
  /// all; skipped, with a warning, on a mesh that does not conform.
  bool restore_volumes = true;

  Mesh3Optimisation optimise;           ///< optimisation and sliver repair (mesh3_optimisation.h)

  /// Reads the `direct:` map (unknown keys are errors; values range-checked with the key named).
  static DirectMeshParams from_yaml(YamlMap& map);
  /// The absorption threshold in voxels of `voxel_mm3`: components with fewer voxels go (<= 1: none).
  std::size_t absorb_below_voxels(double voxel_mm3) const;
  void to_yaml(YAML::Emitter& out) const;
};

}  // namespace tissuemesh
