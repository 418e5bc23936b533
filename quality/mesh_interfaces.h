// The multi-material surface of a tetrahedral mesh: every face between two regions
// (tissue|tissue, or tissue|outside on the mesh boundary) once, as a TriSurface with its label
// pair p < q, wound so that its normal points from p into q, and the junction polylines where
// three or more regions meet. Faces inside one tissue are left out.
//
// This is the geometry a second mesher must reproduce to mesh "the same model": `check --tetgen`
// hands it to TetGen (volume/tetgen_mesher.h), so the two meshes share every boundary and
// interface triangle. Points are the mesh nodes the surface uses, in node order. Deterministic.
#pragma once

#include "core/tet_mesh.h"
#include "core/tri_surface.h"

#include <vector>

namespace tissuemesh {

/// Throws InputError when a face is shared by more than two tets (not a conforming mesh). When
/// `node_of_point` is given, it receives the mesh node of every surface point.
TriSurface interface_surface(const TetMesh& mesh, std::vector<int>* node_of_point = nullptr);

}  // namespace tissuemesh
