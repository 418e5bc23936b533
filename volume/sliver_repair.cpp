// repair_slivers (volume/mesh3_optimisation.h). Kept apart from the settings' parser in
// mesh3_optimisation.cpp so that reading a config needs none of the repair steps.
#include "volume/mesh3_optimisation.h"

#include "core/face_key.h"

#include <algorithm>

namespace tissuemesh {

namespace {
constexpr double kSplitSliversBelowDeg = 10.0;
}  // namespace

SliverRepair repair_slivers(TetMesh& mesh, const Mesh3Optimisation& options, std::vector<std::string>& warnings,
                            const SurfaceProjector& onto_surface) {
  SliverRepair r;
  const bool wanted = options.remove_boundary_slivers_deg > 0 || options.flip_slivers_below_deg > 0 ||
                      options.smooth_slivers_below_deg > 0 || options.open_boundary_pinches;
  if (wanted && mesh.points.size() >= kMaxFaceKeyNodes) {
    warnings.push_back("sliver repair skipped: the mesh has more than 2,097,151 nodes");
    return r;
  }
  if (options.remove_boundary_slivers_deg > 0)
    r.boundary_slivers = remove_boundary_slivers(mesh, options.remove_boundary_slivers_deg);
  if (options.flip_slivers_below_deg > 0)
    r.sliver_flips = flip_slivers(mesh, options.flip_slivers_below_deg, options.interface_flips);
  if (options.smooth_slivers_below_deg > 0)
    r.sliver_smoothing = smooth_slivers(mesh, options.smooth_slivers_below_deg, options.smooth_near_planar_deg,
                                        onto_surface);
  // Splits add nodes, so they are kept for what is still below 10 degrees (the bar of the quality
  // report), not the smoothing's higher target: meshes without such tets stay as they were.
  if (options.smooth_slivers_below_deg > 0)
    r.sliver_splits = split_slivers(mesh, std::min(kSplitSliversBelowDeg, options.smooth_slivers_below_deg),
                                    options.split_relabels);
  // Last, so that no later step changes the outer boundary it leaves manifold.
  if (options.open_boundary_pinches) r.boundary_pinches = tissuemesh::open_boundary_pinches(mesh);
  return r;
}

}  // namespace tissuemesh
