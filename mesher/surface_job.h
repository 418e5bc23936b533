// The surface pipeline's job (issue #5): label image + config -> multi-material surface with its
// checks and quality (the seed paper's Tables 1 and 2 and per-tissue volume against voxel volume).
// Volume meshing from this surface arrives with issue #6. Nothing is printed; stages go through
// `progress`.
#pragma once

#include "core/label_image.h"
#include "core/progress.h"
#include "mesher/mesh_config.h"
#include "mesher/approach_field.h"
#include "mesher/surface_distance.h"
#include "mesher/surface_extraction.h"
#include "mesher/surface_quality.h"
#include "mesher/surface_remesh.h"

#include <map>
#include <optional>
#include <string>

namespace tissuemesh {

struct SurfaceJobResult {
  SurfaceExtraction extraction;             ///< extracted surface, repair, vertex counts and its checks
  SurfaceQuality extracted_quality;         ///< Table 1 figures of the extracted surface
  std::optional<RemeshResult> remesh;       ///< when the config asks for remeshing
  std::optional<SurfaceDistance> hausdorff; ///< remeshed vs extracted surface
  std::optional<ApproachField> approach;    ///< when approach.enabled
  std::optional<ApproachGrading> grading;   ///< measured on surface() when approach.enabled
  SurfaceCheckReport checks;                ///< of surface()
  SurfaceQuality quality;                   ///< Table 1 figures of surface()
  std::map<int, double> voxel_volume_mm3;   ///< tissue id -> voxel volume of the tissue

  /// The pipeline's result: the remeshed surface, or the extracted one without remeshing.
  const TriSurface& surface() const { return remesh ? remesh->surface : extraction.surface; }
};

/// Throws InputError for bad labels (see tissue_id_image), MeshingError when the image has no
/// boundary. A surface failing its checks is returned (the caller reports it), not thrown.
SurfaceJobResult run_surface_job(const LabelImage& labels, const std::string& image_name, const MeshConfig& config,
                                 Progress& progress);

}  // namespace tissuemesh
