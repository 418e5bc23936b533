// The surface pipeline's volume stage with TetGen (`volume.mesher: tetgen`): the tet mesh of the
// remeshed surface itself, every surface triangle kept (volume/tetgen_mesher.h), so nothing is
// resampled: each tissue's meshed volume is the volume its surface encloses, and the tet count is
// what the surface and the interior need (CGAL Mesh_3, volume/complex_mesher.h, resamples the
// surface with its own facets, about 1.8 nodes per surface vertex; docs/surface-pipeline.md).
//
// Sizes: TetGen's largest tet circumradius at each surface point is that of the regular tet of
// edge cell_edge_factor * h(x) (h: the surface's size field, mm); TetGen interpolates it at the
// points it adds, so the interior follows the surface's sizes. cell_edge_factor 0: no size bound,
// TetGen's quality refinement alone grades the interior (the fewest tets). Quality: TetGen's -q
// bounds (TetgenParams::radius_edge_ratio, min_dihedral_deg). Then the sliver repairs that leave
// the surface where it is (volume/mesh3_optimisation.h): flips inside one tissue, vertex moves
// inside a tissue or within an exactly flat patch, splits of edges inside one tissue; never the
// boundary sliver removal, interface flips or moves over curved patches. open_boundary_pinches as
// configured (it acts only where the surface's outer boundary touches itself along an edge).
// Slivers whose four vertices are on the surface and that are still under 10 degrees after all of
// these get the last resort of sliver_offset_edge_ratio: those vertices move off the surface by at
// most that fraction of their mean edge (the tet mesh's boundary and interfaces then differ from
// `surface` there).
//
// Tet budget (`volume.target_tets` > 0): first the mesh without a size bound, the fewest tets
// TetGen gives; within 10 % of the budget it is kept, further above it the budget is an InputError
// naming that count. Below, cell_edge_factor is solved in [0.1, 3] by meet_count_budget
// (volume/budget_refinement.h) with the measure cell_edge_factor^-3, the count of a size-bounded
// mesh growing about as the inverse cube of its edge; a count still more than 10 % off is an
// InputError naming the counts.
//
// Units mm. Deterministic.
#pragma once

#include "core/progress.h"
#include "core/tet_mesh.h"
#include "core/tri_surface.h"
#include "volume/budget_refinement.h"
#include "volume/mesh3_optimisation.h"
#include "volume/tetgen_params.h"
#include "volume/volume_mesh_params.h"

#include <Eigen/Core>

#include <functional>
#include <string>
#include <vector>

namespace tissuemesh {

struct SurfaceTetgenResult {
  TetMesh mesh;
  std::string switches;              ///< TetGen's switches of the mesh kept
  std::size_t steiner_points = 0;    ///< nodes TetGen added to the surface's (before the repairs)
  double cell_edge_factor = 0.0;     ///< the factor of the mesh kept (0: no size bound; solved under a budget)
  /// The TetGen runs under volume.target_tets (empty without): first the one without a size bound
  /// (measure 0), then the rounds of meet_count_budget (measure cell_edge_factor^-3).
  std::vector<BudgetRound> budget;
  SliverRepair repair;               ///< what the surface-preserving repairs did
  std::vector<std::string> warnings;
};

/// Meshes the valid `surface` with TetGen (see the header comment); `size_mm` is h(x), positive and
/// finite at every surface point. params: cell_edge_factor, target_tets and the repair thresholds
/// of params.optimise (flip_slivers_below_deg, smooth_slivers_below_deg) are read; tetgen: the -q
/// bounds. Throws InputError for an invalid surface, bad parameters or a budget that cannot be
/// met (naming volume.target_tets and the counts), MeshingError when TetGen fails.
SurfaceTetgenResult mesh_surface_with_tetgen(const TriSurface& surface,
                                             const std::function<double(const Eigen::Vector3d&)>& size_mm,
                                             const VolumeMeshParams& params, const TetgenParams& tetgen,
                                             Progress& progress);

}  // namespace tissuemesh
