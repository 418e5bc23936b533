// Parameters of the surface pipeline (config section `surface:`; docs/configuration.md,
// "Surface pipeline").
//
//   surface:
//     min_island_voxels: 8        # tissue components with fewer voxels join their surroundings (1 = keep all)
//     relaxation_iterations: 10   # Taubin lambda|mu pairs of the constrained relaxation (0 = voxel corners)
//     target_vertices: 0          # total vertex budget of the remeshed complex (0 = no remeshing)
//     target_edge_mm: 0           # or a target edge length in mm (used when target_vertices is 0)
//     remesh_iterations: 10       # split/collapse/flip/relax rounds (surface/surface_remesh.h)
//     restore_volumes: false      # offset the remeshed patches so every tissue has its voxel volume
//     thickness_edge_ratio: 1     # edges at most this times the local thickness of thin parts (0 = off)
//     mean_quality_passes: 0      # passes raising the mean triangle quality at the end (0 = none)
#pragma once

#include "core/yaml_map.h"

namespace tissuemesh {

struct SurfaceParams {
  /// Tissue components with fewer voxels take the region around them before extraction
  /// (image/small_islands.h); 1 keeps every component.
  int min_island_voxels = 8;
  int relaxation_iterations = 10;  ///< Taubin lambda|mu pairs (surface/surface_extraction.h); 0 = none
  int target_vertices = 0;         ///< remeshing vertex budget; 0 = none (see target_edge_mm)
  double target_edge_mm = 0.0;     ///< remeshing edge length, mm, when target_vertices == 0; 0 = none
  int remesh_iterations = 10;      ///< rounds of surface/surface_remesh.h
  /// After remeshing, offset the patches along their normals so that every tissue encloses its
  /// voxel volume again (surface/volume_restoration.h).
  bool restore_volumes = false;
  /// Remeshed edges at most this times the local thickness of the tissues (image/local_thickness.h)
  /// where that is under the edge length, coarsened as a whole when the thin parts would take more
  /// than half the vertex budget (surface/thickness_size.h, surface/surface_remesh.h); 0 = off.
  double thickness_edge_ratio = 1.0;
  /// Passes of the mean-quality smoothing that ends the remeshing (RemeshOptions::
  /// mean_quality_passes, surface/surface_remesh.h); 0 = none.
  int mean_quality_passes = 0;

  bool remesh() const { return target_vertices > 0 || target_edge_mm > 0.0; }

  /// Reads the `surface:` map (unknown keys are errors; values range-checked with the key named).
  static SurfaceParams from_yaml(YamlMap& map);
  void to_yaml(YAML::Emitter& out) const;
};

}  // namespace tissuemesh
