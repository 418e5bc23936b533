// Volume mesher of the surface pipeline: CGAL Mesh_3 from a multi-material surface complex (CGAL
// 3D Mesh Generation manual, "Domains Bounded by a Polyhedral Complex"), all tissues at once, so
// every interface is conforming by construction. See docs/surface-pipeline.md, section 4.
//
// Input: a valid TriSurface (surface/surface_checks.h), cut into manifold pieces
// (volume/surface_pieces.h); each piece is one polyhedron of Polyhedral_complex_mesh_domain_3
// with its incident subdomains (p on the side opposite the normal, q on the normal's side). Piece
// borders (junction curves) and creases sharper than feature_angle_deg are protected as polyline
// features; pieces without borders get initial points of their own. Sizes follow `size_mm(x)`
// (the surface's field h(x), mm; volume_mesh_params.h gives the factors). Then the optimisation
// and sliver repairs of Mesh3Optimisation.
//
// A tet budget (params.target_tets > 0): every size and the facet distance are multiplied by one
// factor, solved by the rounds of volume/budget_refinement.h (count about 1 / factor here), each
// round a CGAL refinement; the last round's is kept. A facet must then have its vertices on one
// patch (CGAL's FACET_VERTICES_ON_SAME_SURFACE_PATCH), so the larger facet distance never lets a
// facet bridge a thin layer. CGAL resamples the surface, so the tets then have fewer boundary
// nodes than the surface has vertices (the seed paper's Table 2 shows the same).
//
// Volume restoration (`restore_to_mm3` not empty): after the sliver repair, the boundary and
// interface nodes move so that every tissue's tets fill its reference volume again
// (volume/tet_volume_restoration.h); the chords of the resampling otherwise cut every curved sheet.
//
// Output: tets positively oriented, coordinates the input's (LPS mm). The boundary approximates
// the input surface to within the facet distance (plus the restoration's offsets); it is not the
// input surface itself (the TetGen backend keeps that exactly). Deterministic.
#pragma once

#include "core/progress.h"
#include "core/tet_mesh.h"
#include "core/tri_surface.h"
#include "volume/mesh3_optimisation.h"
#include "volume/tet_volume_restoration.h"
#include "volume/volume_mesh_params.h"

#include <Eigen/Core>

#include <cstddef>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace tissuemesh {

/// One round under volume.target_tets.
struct SizeRound {
  double factor = 1.0;    ///< the factor every size was multiplied by
  std::size_t tets = 0;   ///< tets it gave (after restoration and sliver repair)
};

struct ComplexMeshResult {
  TetMesh mesh;
  std::size_t pieces = 0;            ///< manifold patch pieces given to CGAL
  std::size_t duplicated_vertices = 0;  ///< non-manifold piece vertices split per fan
  std::size_t initial_points = 0;    ///< protecting balls plus points on borderless pieces
  SliverRepair repair;               ///< what the sliver repairs did
  std::vector<std::string> warnings; ///< e.g. an optimiser stopped by its time limit
  double size_factor = 1.0;          ///< the factor of the mesh kept (1 without a budget)
  std::vector<SizeRound> budget;     ///< the rounds under volume.target_tets (empty without)
  std::optional<TetVolumeRestoration> restoration;  ///< when reference volumes were given
};

/// Meshes `surface` (see the header comment). `size_mm` must be positive and finite everywhere
/// near the surface. `restore_to_mm3`: tissue id -> reference volume (mm^3), empty for none.
/// Throws InputError for an invalid surface or a budget that cannot be met (naming
/// volume.target_tets and the counts reached), MeshingError if CGAL yields no tets.
ComplexMeshResult mesh_complex(const TriSurface& surface, const std::function<double(const Eigen::Vector3d&)>& size_mm,
                               const VolumeMeshParams& params, Progress& progress,
                               const std::map<int, double>& restore_to_mm3 = {});

}  // namespace tissuemesh
