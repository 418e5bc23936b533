// Removal of slivers that lie on the outer boundary of a tet mesh.
//
// A sliver with two or more faces on the outer boundary (faces with no neighbour) is a flat cap:
// removing it changes the boundary by a flip of its faces and the volume by the sliver's own,
// near-zero volume, and it cannot be repaired by moving vertices that must stay on the surface.
// Interface slivers (between two tissues) and interior ones are left alone: removing them would
// open a gap. Nodes no tet uses any more are dropped. Deterministic.
#pragma once

#include "core/tet_mesh.h"

#include <cstddef>
#include <vector>

namespace tissuemesh {

struct BoundarySliverRemoval {
  std::size_t tets_removed = 0;
  double volume_removed_mm3 = 0.0;
  std::vector<std::size_t> removed_per_tissue;  ///< index = tissue id - 1
};

/// Removes (repeatedly, as removal exposes new boundary faces) every tet whose smallest dihedral
/// angle is below `min_dihedral_deg` and that has at least two faces on the outer boundary.
BoundarySliverRemoval remove_boundary_slivers(TetMesh& mesh, double min_dihedral_deg);

}  // namespace tissuemesh
