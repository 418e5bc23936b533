// Example 01: mesh a label image through the library API, no files needed.
//
// Builds a 40 x 40 x 27 label image of two nested spheres (1 mm x 1 mm x 1.5 mm voxels), maps the
// labels to tissues with a config given as YAML text, meshes it with the direct pipeline and
// prints what a user checks first: counts, per-tissue volume against the voxel volume, the
// smallest dihedral angle and conformity. Exit code 0 when the mesh is conforming.
#include "pipeline/mesh_job.h"
#include "pipeline/mesh_report.h"

#include <iostream>

int main() {
  using namespace tissuemesh;
  LabelImage labels;
  labels.dims = {40, 40, 27};
  labels.spacing = {1.0, 1.0, 1.5};
  labels.labels.resize(labels.voxel_count());
  for (int k = 0; k < labels.dims[2]; ++k)
    for (int j = 0; j < labels.dims[1]; ++j)
      for (int i = 0; i < labels.dims[0]; ++i) {
        const double r = Eigen::Vector3d(i - 19.5, j - 19.5, 1.5 * (k - 13)).norm();
        labels.labels[labels.index(i, j, k)] = r < 8 ? 2 : (r < 16 ? 1 : 0);
      }

  const MeshConfig config = MeshConfig::parse(YAML::Load(R"(
tissues:
  - {name: fat,   labels: [1]}
  - {name: tumor, labels: [2]}
direct: {facet_size_mm: 2.5, cell_size_mm: 4, refine_size_mm: 1.5, refine_radius_mm: 6}
)"), "example config");

  Progress progress;  // silent; pass a sink to see stages
  const MeshJobResult result = run_mesh_job(labels, "two spheres", config, progress);
  std::cout << mesh_job_text(result);
  return result.conformity.conforming() ? 0 : 1;
}
