// Direct pipeline: CGAL Mesh_3 from a tissue-id image to one conforming multi-material TetMesh
// (CGAL 3D Mesh Generation manual, labelled image domains; docs/direct-pipeline.md).
//
// Method: tissue components below the size threshold of DirectMeshParams join the region around
// them (image/small_islands.h); tissues that touch the image border end at the centres of the
// border voxels, where polylines are protected as features; boundaries are smoothed by weighted
// labels (label_weights.h); every remaining 6-connected component of every tissue gets initial
// surface points, so that no island is skipped (one start voxel per facet_size_mm cube of its
// volume, at least one and at most nine, six axis rays from each: at most 54 points per component
// and 6 per small one); Delaunay refinement with the criteria of DirectMeshParams and a size
// field that is finer around `refine_tissue`, or, with a tet budget, sizes from each tissue's local
// thickness scaled to meet the budget (image_sizing.h); then optional Lloyd/ODT, sliver
// perturbation/exudation and the sliver repairs of Mesh3Optimisation; then small enclosed
// components are scaled to their voxel volume (component_volume_fit.h), and, with
// restore_volumes, every tissue's boundary and interface nodes move so that its tets fill its voxel
// volume (tet_volume_restoration.h). All tets of the result are
// positively oriented in physical LPS millimetres, even when the image direction matrix is a
// reflection. Deterministic: the same image and parameters give the same mesh.
#pragma once

#include "core/label_image.h"
#include "core/progress.h"
#include "core/tet_mesh.h"
#include "image/small_islands.h"
#include "volume/budget_refinement.h"
#include "volume/component_volume_fit.h"
#include "volume/direct_mesh_params.h"
#include "volume/image_sizing.h"
#include "volume/tet_volume_restoration.h"
#include "volume/mesh3_optimisation.h"

#include <Eigen/Core>

#include <map>
#include <optional>
#include <string>
#include <vector>

namespace tissuemesh {

/// A connected part of a tissue in the image that no tet of that tissue covers.
struct MissedComponent {
  std::string tissue;
  std::size_t voxels = 0;
  double volume_mm3 = 0.0;
  Eigen::Vector3d centroid_mm{0, 0, 0};  ///< LPS
};

struct DirectMeshResult {
  TetMesh mesh;
  std::size_t image_components = 0;      ///< 6-connected components over all tissues of the input
  /// Components under DirectMeshParams::absorb_below_voxels, given to their surroundings.
  IslandAbsorption absorbed;
  std::size_t meshed_components = 0;     ///< components left to mesh, each seeded and checked
  std::size_t initial_points = 0;        ///< surface points seeded before refinement
  std::vector<MissedComponent> missed;   ///< kept components not represented (reported, never hidden)
  SliverRepair repair;                   ///< what the sliver repairs did
  DirectSizing sizing;                   ///< with direct.target_tets: sizes and counts
  ComponentVolumeFit island_fit;         ///< small enclosed components scaled to their voxel volume
  /// With params.restore_volumes on a conforming mesh: the tets' volume restoration.
  std::optional<TetVolumeRestoration> restoration;
  /// Things the user must know, e.g. an optimiser stopped by its time limit (its result then
  /// depends on machine speed, so repeated runs may differ).
  std::vector<std::string> warnings;
};

/// `ids`: tissue ids 0..N (0 = outside) as made by TissueTable::to_tissue_ids; `tissue_names[i]`
/// names id i+1. With params.target_tets > 0 the sizes come from the image (image_sizing.h) and
/// refinement is repeated (at most four times) until the count is within 5 % of the budget; a
/// count still more than 10 % off throws InputError naming the counts reached and the budget this
/// image can meet. Throws InputError if a name in params (cell_size_per_tissue_mm, refine_tissue)
/// is not a tissue, MeshingError if CGAL yields no tets.
DirectMeshResult mesh_labels_direct(const LabelImage& ids, const std::vector<std::string>& tissue_names,
                                    const DirectMeshParams& params, Progress& progress);

/// "5.5.1" — the CGAL version this library was built with.
std::string cgal_version();

}  // namespace tissuemesh
