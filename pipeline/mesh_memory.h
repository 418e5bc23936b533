// The memory a `mesh` job needs, estimated before meshing starts, so that a job that cannot fit is
// refused with the numbers (voxels, expected tets) instead of being killed by the OOM killer.
//
// Estimate (from bench/RESULTS.md's measured peaks: 186,542 tets in 207 MiB; 32.8 M voxels and
// 288,486 tets in 1015 MiB): 24 bytes per voxel (the labels, the tissue-id image, components and
// distance fields held at once) plus 1,200 bytes per tet (CGAL's triangulation, the TetMesh and
// the quality arrays). Expected tets: `direct.target_tets` when set, else the tissue volume divided
// by the volume of a regular tet whose circumradius is `direct.cell_size_mm` (0.513 R^3). Mesh_3
// usually makes more, smaller tets near surfaces, so this is a lower bound: a job refused by it
// cannot fit, a job let through may still need more. The surface pipeline's own sizes are not
// modelled; its estimate is the voxel part.
#pragma once

#include "core/label_image.h"
#include "pipeline/mesh_config.h"

#include <cstdint>
#include <string>

namespace tissuemesh {

struct MeshMemoryEstimate {
  std::uint64_t voxels = 0;
  std::uint64_t tissue_voxels = 0;   ///< voxels of a mapped tissue (not ignored)
  std::uint64_t expected_tets = 0;   ///< lower bound, see above
  std::uint64_t bytes = 0;
};

MeshMemoryEstimate estimate_mesh_memory(const LabelImage& labels, const MeshConfig& config);

/// Throws InputError naming `image_name` with the estimate when it exceeds the memory available
/// (core/memory_budget.h).
void require_mesh_memory(const LabelImage& labels, const MeshConfig& config,
                         const std::string& image_name);

}  // namespace tissuemesh
