// Label maps without background, and a tiny tissue: two traits of real label maps that the
// generators (make_phantom) add on request.
//
// A map with no label 0 has no "outside" inside the image: the mesh's outer boundary is the image
// box, and tissue interfaces run into its faces and corners. A tissue of a few tens of voxels
// (a biopsy marker clip, a small lesion) is at the voxel scale: any feature-size threshold loses
// it. Both functions work in index space and are deterministic (same input and seed -> same bytes).
#pragma once

#include "core/label_image.h"

#include <cstddef>
#include <cstdint>

namespace tissuemesh {

/// Voxel radius of the tiny tissue: a ball of voxel centres within 2 voxels of its centre voxel
/// (in index units), i.e. 33 voxels.
constexpr int kTinyTissueRadiusVoxels = 2;

/// Replaces every label 0 by `fill` (> 0). Returns the number of voxels changed.
std::size_t fill_background(LabelImage& image, std::int32_t fill);

/// Paints a ball of kTinyTissueRadiusVoxels (33 voxels) with `label`, at a voxel chosen by `seed`
/// among those whose ball grown by one more voxel holds only `host` (so the tiny tissue touches
/// only `host`, never the image border). Returns the number of voxels painted. Throws
/// MeshingError if no such place is found after 200,000 seeded tries and a full scan.
std::size_t add_tiny_tissue(LabelImage& image, std::int32_t host, std::int32_t label,
                            std::uint32_t seed);

}  // namespace tissuemesh
