// The `mesh` job: label image + config -> tet mesh + quality/conformity/fidelity report.
//
// Steps: check the image against the tissue table (unknown labels, empty tissues -> InputError),
// map labels to tissue ids, mesh with the configured pipeline, then measure: per-tissue quality
// with the voxel volume of each tissue as reference, conformity, and image components that the
// mesh does not represent. Nothing is printed; stages go through `progress`.
#pragma once

#include "core/label_image.h"
#include "core/progress.h"
#include "quality/conformity.h"
#include "volume/direct_mesher.h"
#include "pipeline/mesh_config.h"
#include "quality/mesh_quality.h"

#include <map>
#include <string>

namespace tissuemesh {

struct MeshJobResult {
  DirectMeshResult meshing;                 ///< mesh, component counts, missed components
  std::map<int, double> voxel_volume_mm3;   ///< tissue id -> voxel volume of the tissue
  QualityReport quality;
  ConformityReport conformity;
  std::vector<VolumeDeviation> volume_deviations;  ///< tissues outside checks.volume_tolerance_percent
};

/// The first step of every pipeline: checks `labels` against the tissue table (unknown labels,
/// empty tissues -> InputError naming `image_name`) and returns the tissue-id image (0 = outside);
/// `voxel_volume_mm3` receives each tissue's voxel volume.
LabelImage tissue_id_image(const LabelImage& labels, const std::string& image_name, const TissueTable& tissues,
                           std::map<int, double>& voxel_volume_mm3, Progress& progress);

/// The direct pipeline. `image_name` names the image in error messages.
MeshJobResult run_mesh_job(const LabelImage& labels, const std::string& image_name,
                           const MeshConfig& config, Progress& progress);

}  // namespace tissuemesh
