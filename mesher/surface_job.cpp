#include "mesher/surface_job.h"

#include "mesher/mesh_job.h"

namespace tissuemesh {

SurfaceJobResult run_surface_job(const LabelImage& labels, const std::string& image_name, const MeshConfig& config,
                                 Progress& progress) {
  SurfaceJobResult r;
  const LabelImage ids = tissue_id_image(labels, image_name, config.tissues, r.voxel_volume_mm3, progress);
  r.extraction = extract_surface(ids, config.tissues.names(), config.surface, progress);
  auto stage = progress.stage("surface quality");
  r.quality = surface_quality(r.extraction.surface);
  return r;
}

}  // namespace tissuemesh
