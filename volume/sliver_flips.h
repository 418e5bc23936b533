// Sliver removal by topological flips that never touch a tissue interface or the boundary.
//
// For each tet whose smallest dihedral angle is below a target, the best of these is applied if
// it raises the smallest dihedral angle of the tets it replaces (Shewchuk, "Two discrete
// optimization algorithms for the topological improvement of tetrahedral meshes", 2002):
//  - 2-3 flip: two tets sharing a face -> three tets around the edge joining their apexes;
//  - edge removal: the n = 3..7 tets around an edge -> 2(n-2) tets, the ring polygon triangulated
//    by dynamic programming to maximise the worst new tet (n = 3 is the 3-2 flip).
// Only cells of one tissue take part and every replaced region keeps its outer faces, so tissue
// volumes, interfaces, boundary and conformity are unchanged; nodes are neither added nor moved.
// Optionally (interface flips) a flat wedge whose two faces on one edge lie on the same
// neighbouring tissue is first given to that tissue, which flips the interface's diagonal across
// the wedge and makes the edge removable: the interface moves by the wedge's thickness and the
// wedge's (near-zero) volume changes tissue; both are reported. The wedge is either the bad tet
// itself (given to the tissue around its edge) or one other tet around an edge of the bad tet
// (given to the bad tet's tissue; e.g. a sliver lying on an interface next to a flat wedge of the
// other tissue). Only one wedge changes per flip, and only if no tissue is pinched, split or
// joined by it: either its other two faces border its own tissue and every other tet around its
// opposite edge is of that tissue, or the local test of wedge_relabel.h holds.
// Deterministic (bad tets in order of quality, then index).
#pragma once

#include "core/tet_mesh.h"

#include <cstddef>

namespace tissuemesh {

struct SliverFlipResult {
  std::size_t flips_23 = 0;        ///< 2-3 flips applied
  std::size_t edge_removals = 0;   ///< edge removals applied (3-2 flips and interface flips included)
  std::size_t interface_flips = 0; ///< edge removals that relabelled a flat interface wedge
  double volume_relabelled_mm3 = 0.0;  ///< total volume of those wedges (moved between tissues)
  std::size_t passes = 0;          ///< sweeps over the bad tets
};

/// Improves tets with a dihedral angle below `target_deg` (degrees), at most `max_passes` sweeps.
SliverFlipResult flip_slivers(TetMesh& mesh, double target_deg, bool allow_interface_flips,
                              int max_passes = 8);

}  // namespace tissuemesh
