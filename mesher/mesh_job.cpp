#include "mesher/mesh_job.h"

namespace tissuemesh {

MeshJobResult run_mesh_job(const LabelImage& labels, const std::string& image_name,
                           const MeshConfig& config, Progress& progress) {
  MeshJobResult r;
  LabelImage ids;
  {
    auto stage = progress.stage("check labels");
    const auto counts = labels.label_counts();
    config.tissues.check_against(counts, image_name);
    ids = config.tissues.to_tissue_ids(labels);
    for (const auto& [label, n] : counts) {
      const int id = config.tissues.tissue_of_label(label);
      if (id > 0) r.voxel_volume_mm3[id] += static_cast<double>(n) * labels.voxel_volume();
    }
  }
  r.meshing = mesh_labels_direct(ids, config.tissues.names(), config.direct, progress);
  {
    auto stage = progress.stage("quality and conformity");
    r.quality = compute_quality(r.meshing.mesh, r.voxel_volume_mm3);
    r.conformity = check_conformity(r.meshing.mesh);
  }
  return r;
}

}  // namespace tissuemesh
