// Volume mesher of the surface pipeline: CGAL Mesh_3 from a multi-material surface complex (CGAL
// 3D Mesh Generation manual, "Domains Bounded by a Polyhedral Complex"), all tissues at once, so
// every interface is conforming by construction. See docs/surface-pipeline.md, section 4.
//
// Input: a valid TriSurface (surface/surface_checks.h), cut into manifold pieces
// (volume/surface_pieces.h); each piece is one polyhedron of Polyhedral_complex_mesh_domain_3
// with its incident subdomains (p on the side opposite the normal, q on the normal's side). Piece
// borders (junction curves) and creases sharper than feature_angle_deg are protected as polyline
// features; pieces without borders get initial points of their own. Sizes follow `size_mm(x)`
// (the surface's field h(x), mm; volume_mesh_params.h gives the factors); then the optimisation
// and sliver repairs of Mesh3Optimisation.
//
// Output: tets positively oriented, coordinates the input's (LPS mm). The boundary approximates
// the input surface to within facet_distance; it is not the input surface itself (the TetGen
// backend keeps that exactly). Deterministic.
#pragma once

#include "core/progress.h"
#include "core/tet_mesh.h"
#include "core/tri_surface.h"
#include "volume/mesh3_optimisation.h"
#include "volume/volume_mesh_params.h"

#include <Eigen/Core>

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

namespace tissuemesh {

struct ComplexMeshResult {
  TetMesh mesh;
  std::size_t pieces = 0;            ///< manifold patch pieces given to CGAL
  std::size_t duplicated_vertices = 0;  ///< non-manifold piece vertices split per fan
  std::size_t initial_points = 0;    ///< protecting balls plus points on borderless pieces
  SliverRepair repair;               ///< what the sliver repairs did
  std::vector<std::string> warnings; ///< e.g. an optimiser stopped by its time limit
};

/// Meshes `surface` (see the header comment). `size_mm` must be positive and finite everywhere
/// near the surface. Throws InputError for an invalid surface, MeshingError if CGAL yields no tets.
ComplexMeshResult mesh_complex(const TriSurface& surface, const std::function<double(const Eigen::Vector3d&)>& size_mm,
                               const VolumeMeshParams& params, Progress& progress);

}  // namespace tissuemesh
