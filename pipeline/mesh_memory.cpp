#include "pipeline/mesh_memory.h"

#include "core/memory_budget.h"
#include "core/number_format.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace tissuemesh {
namespace {

constexpr double kBytesPerVoxel = 24.0;
constexpr double kBytesPerTet = 1200.0;
// Volume of a regular tetrahedron of circumradius R: edge a = R sqrt(8/3), V = a^3 / (6 sqrt 2).
constexpr double kRegularTetVolumePerR3 = 0.5132;

std::uint64_t saturate(double value) {
  return value >= 1.8e19 ? std::numeric_limits<std::uint64_t>::max()
                         : static_cast<std::uint64_t>(std::max(0.0, value));
}

}  // namespace

MeshMemoryEstimate estimate_mesh_memory(const LabelImage& labels, const MeshConfig& config) {
  MeshMemoryEstimate e;
  e.voxels = labels.voxel_count();
  for (std::int32_t label : labels.labels) e.tissue_voxels += config.tissues.tissue_of_label(label) > 0;
  const double tissue_mm3 = static_cast<double>(e.tissue_voxels) * labels.voxel_volume();
  const double radius = config.direct.cell_size_mm;
  double tets = 0.0;
  if (config.pipeline == "direct") {
    tets = config.direct.target_tets > 0
               ? static_cast<double>(config.direct.target_tets)
               : tissue_mm3 / (kRegularTetVolumePerR3 * radius * radius * radius);
  }
  e.expected_tets = saturate(std::ceil(tets));
  e.bytes = saturate(kBytesPerVoxel * static_cast<double>(e.voxels) + kBytesPerTet * tets);
  return e;
}

void require_mesh_memory(const LabelImage& labels, const MeshConfig& config,
                         const std::string& image_name) {
  const MeshMemoryEstimate e = estimate_mesh_memory(labels, config);
  require_memory(e.bytes, image_name + ": meshing this image",
                 std::to_string(e.voxels) + " voxels, at least " + std::to_string(e.expected_tets) +
                     " tets expected at direct.cell_size_mm = " +
                     format_double("%g", config.direct.cell_size_mm) + " mm");
}

}  // namespace tissuemesh
