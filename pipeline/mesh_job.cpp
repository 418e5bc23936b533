#include "pipeline/mesh_job.h"

#include "core/errors.h"

#include <algorithm>

namespace tissuemesh {

LabelImage tissue_id_image(const LabelImage& labels, const std::string& image_name, const TissueTable& tissues,
                           std::map<int, double>& voxel_volume_mm3, Progress& progress) {
  auto stage = progress.stage("check labels");
  // An image one voxel thin along an axis gives CGAL Mesh_3 no facet to start from: it stops with
  // no tetrahedra, after printing a warning of its own.
  if (*std::min_element(labels.dims.begin(), labels.dims.end()) < 2) {
    throw InputError(image_name + ": " + std::to_string(labels.dims[0]) + " x " +
                     std::to_string(labels.dims[1]) + " x " + std::to_string(labels.dims[2]) +
                     " voxels: a volume mesh needs at least 2 voxels along each axis");
  }
  const auto counts = labels.label_counts();
  tissues.check_against(counts, image_name);
  for (const auto& [label, n] : counts) {
    const int id = tissues.tissue_of_label(label);
    if (id > 0) voxel_volume_mm3[id] += static_cast<double>(n) * labels.voxel_volume();
  }
  return tissues.to_tissue_ids(labels);
}

MeshJobResult run_mesh_job(const LabelImage& labels, const std::string& image_name,
                           const MeshConfig& config, Progress& progress) {
  MeshJobResult r;
  const LabelImage ids = tissue_id_image(labels, image_name, config.tissues, r.voxel_volume_mm3, progress);
  r.meshing = mesh_labels_direct(ids, config.tissues.names(), config.direct, progress);
  {
    auto stage = progress.stage("quality and conformity");
    r.quality = compute_quality(r.meshing.mesh, r.voxel_volume_mm3);
    r.conformity = check_conformity(r.meshing.mesh);
    r.volume_deviations = volume_deviations(r.quality, config.checks);
    for (std::string& w : volume_warnings(r.volume_deviations, config.checks)) r.meshing.warnings.push_back(std::move(w));
  }
  return r;
}

}  // namespace tissuemesh
