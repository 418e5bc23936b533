// Sliver removal by splitting an edge inside one tissue: where flips and vertex moves cannot help
// (a flat tet spanning a thin sheet of tissue, its four vertices on the sheet's two faces, every
// vertex pinned to an interface), a new vertex inside the tissue can.
//
// For each tet whose smallest dihedral angle is below `target_deg` (in order of quality, then
// index), its edges no boundary or interface face contains (all tets around such an edge are of
// one tissue and the ring of tets around it is closed) are tried, longest first: the edge (a, b) is
// split at its midpoint m (each tet around it becomes two, a -> m and b -> m, both positively
// oriented), m moves by a compass search to maximise the smallest dihedral angle of its star, and
// the split is kept only when that star's smallest angle exceeds the smallest angle of the tets it
// replaced and no more of its tets are under `target_deg` than of those. m stays inside the tissue (its star stays positively oriented), so tissue volumes,
// interfaces, the boundary and conformity are unchanged. Deterministic.
// Optionally (interface relabels), when no such edge helps and the bad tet is a flat wedge whose
// every neighbour around one of its edges is of one other tissue (a sliver on an interface, e.g.
// with three faces on interfaces), the wedge is first given to that tissue, which makes the edge
// one inside it; the relabel is kept only with the split, and only if it keeps every tissue's
// local topology (wedge_relabel.h). Its (near-zero) volume changes tissue and is reported.
#pragma once

#include "core/tet_mesh.h"

#include <cstddef>

namespace tissuemesh {

struct SliverSplitResult {
  std::size_t splits = 0;                ///< edges split (one new node each)
  std::size_t relabelled_wedges = 0;     ///< of them, splits that first gave a flat wedge to another tissue
  double volume_relabelled_mm3 = 0.0;    ///< total volume of those wedges (moved between tissues)
};

/// Splits edges of tets below `target_deg` (degrees) as above, relabelling flat interface wedges
/// when `allow_interface_relabels`; at most `max_passes` sweeps over the bad tets.
SliverSplitResult split_slivers(TetMesh& mesh, double target_deg, bool allow_interface_relabels, int max_passes = 2);

}  // namespace tissuemesh
