// Opening of boundary pinches: edges where the outer boundary of a tet mesh is not a 2-manifold.
//
// Where two parts of the meshed body touch along an edge (a thin gap of outside closed in the
// label image, two voxels of a tissue meeting only at a corner), the edge carries four or more
// outer-boundary faces: the tets around it form two or more fans separated by outside. Such an
// edge fails the conformity check (quality/conformity.h). This step keeps, at every such edge, the
// fan of largest volume and removes the tets of the other fans (a few tets, the smallest side of
// the contact), repeating while removals expose new pinches. Edges with a single boundary face
// (holes) cannot be repaired by removal and are left for the check to report. Nodes no tet uses
// any more are dropped. Deterministic (edges in key order, ties by lowest tet index).
#pragma once

#include "core/tet_mesh.h"

#include <cstddef>
#include <vector>

namespace tissuemesh {

struct BoundaryPinchRepair {
  std::size_t edges_found = 0;       ///< pinched edges in the mesh as given
  std::size_t tets_removed = 0;
  double volume_removed_mm3 = 0.0;
  std::vector<std::size_t> removed_per_tissue;    ///< index = tissue id - 1
  std::vector<double> volume_per_tissue_mm3;      ///< index = tissue id - 1
  std::size_t edges_left = 0;        ///< pinched edges still there when the pass cap ended it
  int passes = 0;
};

/// Opens every pinched boundary edge of `mesh` (at most `max_passes` passes). Requires node ids
/// below kMaxFaceKeyNodes (core/face_key.h); a larger mesh is left as it is (passes = 0).
BoundaryPinchRepair open_boundary_pinches(TetMesh& mesh, int max_passes = 20);

}  // namespace tissuemesh
