// When a flat tet may change tissue: the test the sliver repairs (sliver_flips.h, sliver_splits.h)
// make before giving a thin wedge of one tissue to the tissue on its other side, so that an
// interface edge becomes an edge inside one tissue that a flip or a split can then remove.
//
// A relabel moves no node and changes no face, so the mesh stays conforming and every tissue's
// volume changes by the wedge's volume alone; what it can change is a tissue's topology (two parts
// of a tissue joined or one split at the wedge, a tissue pinched to an edge or a node). The test
// below refuses those: around each node and each edge of the wedge, count the face-connected
// groups of the wedge's tissue and of the receiving tissue. The wedge's tissue may lose a group
// (the wedge was a group of its own there, so a pinch goes away) but not gain one; the receiving
// tissue keeps its count, or reaches a node or edge it did not touch before through the wedge.
#pragma once

#include "core/tet_mesh.h"

#include <functional>

namespace tissuemesh {

/// Largest volume of a "flat" wedge, as a fraction of the regular tet on the wedge's longest edge
/// (L^3 / (6 sqrt 2)): its four nodes are then close to one plane and the interface moves by
/// little. 0.2 admits the flat wedges found next to slivers on phantom interfaces (about 0.15); a
/// moved volume stays below 0.2 L^3 / 8.5, e.g. 0.16 mm^3 at L = 1.9 mm.
inline constexpr double kFlatWedgeFraction = 0.2;

/// True if tet `t` of `mesh` is flat in the sense above (|volume| below kFlatWedgeFraction of the
/// regular tet on its longest edge).
bool is_flat_wedge(const TetMesh& mesh, int t);

/// The other tet than `t` on the face (a, b, c), or -1 (the outer boundary or no such face).
using AcrossFace = std::function<int(int a, int b, int c, int t)>;

/// True if giving tet `t` to tissue `to` keeps every tissue's local topology (see the file comment).
/// Looks at the tets around t's nodes reached through faces containing them; a node with more
/// than 1,024 such tets is refused. `across` gives the face neighbours of the current mesh.
bool relabel_keeps_topology(const TetMesh& mesh, int t, int to, const AcrossFace& across);

}  // namespace tissuemesh
