#include "mesher/surface_job.h"

#include "mesher/mesh_job.h"

namespace tissuemesh {

SurfaceJobResult run_surface_job(const LabelImage& labels, const std::string& image_name, const MeshConfig& config,
                                 Progress& progress) {
  SurfaceJobResult r;
  const LabelImage ids = tissue_id_image(labels, image_name, config.tissues, r.voxel_volume_mm3, progress);
  r.extraction = extract_surface(ids, config.tissues.names(), config.surface, progress);
  r.extracted_quality = surface_quality(r.extraction.surface);
  r.checks = r.extraction.checks;
  r.quality = r.extracted_quality;
  if (!config.surface.remesh() || !r.extraction.checks.valid()) return r;
  const SurfaceProjection on_extracted(r.extraction.surface);
  RemeshOptions options;
  options.target_vertices = config.surface.target_vertices;
  options.target_edge_mm = config.surface.target_edge_mm;
  options.iterations = config.surface.remesh_iterations;
  options.max_deviation_mm = 0.5 * ids.spacing.norm();  // half a voxel diagonal
  if (config.approach.enabled) {
    r.approach.emplace(r.extraction.surface, config.approach);
    const ApproachField* field = &*r.approach;
    options.relative_size = [field](const Eigen::Vector3d& p) { return field->relative_size(p); };
  }
  r.remesh = remesh_surface(r.extraction.surface, on_extracted, options, progress);
  {
    auto stage = progress.stage("remeshed surface quality");
    r.checks = r.remesh->checks;
    r.quality = surface_quality(r.remesh->surface);
    if (r.approach) r.grading = measure_grading(r.remesh->surface, *r.approach);
  }
  auto stage = progress.stage("Hausdorff distance to the extracted surface");
  const SurfaceProjection on_remeshed(r.remesh->surface);
  r.hausdorff = hausdorff_distance(r.remesh->surface, on_remeshed, r.extraction.surface, on_extracted);
  return r;
}

}  // namespace tissuemesh
