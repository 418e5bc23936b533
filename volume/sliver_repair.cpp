// repair_slivers (volume/mesh3_optimisation.h). Kept apart from the settings' parser in
// mesh3_optimisation.cpp so that reading a config needs none of the repair steps.
#include "volume/mesh3_optimisation.h"

#include "core/face_key.h"
#include "quality/mesh_quality.h"

#include <algorithm>

namespace tissuemesh {

namespace {
constexpr double kSplitSliversBelowDeg = 10.0;

bool any_tet_below(const TetMesh& mesh, double deg) {
  for (const auto& k : mesh.tets)
    if (tet_volume_and_min_dihedral(mesh.points[k[0]], mesh.points[k[1]], mesh.points[k[2]], mesh.points[k[3]])
            .min_dihedral_deg < deg)
      return true;
  return false;
}
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
  const double split_below = std::min(kSplitSliversBelowDeg, options.smooth_slivers_below_deg);
  if (options.smooth_slivers_below_deg > 0)
    r.sliver_splits = split_slivers(mesh, split_below, options.split_relabels);
  // The last resort moves the boundary and interfaces, so it waits for everything that keeps them,
  // and runs only where a tet is still under the splits' bar.
  if (options.smooth_slivers_below_deg > 0 && options.sliver_offset_edge_ratio > 0 && any_tet_below(mesh, split_below)) {
    // Every vertex that is not free moves off its surface here, so neither the near-planar angle
    // nor a projector would change what moves.
    r.sliver_offsets = smooth_slivers(mesh, split_below, 0.0, {}, 4, options.sliver_offset_edge_ratio);
    if (r.sliver_offsets.moved_vertices > 0 && any_tet_below(mesh, split_below)) {
      const SliverSplitResult again = split_slivers(mesh, split_below, options.split_relabels);
      r.sliver_splits.splits += again.splits;
      r.sliver_splits.relabelled_wedges += again.relabelled_wedges;
      r.sliver_splits.volume_relabelled_mm3 += again.volume_relabelled_mm3;
    }
  }
  // Last, so that no later step changes the outer boundary it leaves manifold.
  if (options.open_boundary_pinches) r.boundary_pinches = tissuemesh::open_boundary_pinches(mesh);
  return r;
}

}  // namespace tissuemesh
