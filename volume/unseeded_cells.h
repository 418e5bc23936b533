// Tets that TetGen leaves in no region, labelled from the surface triangles around them.
//
// TetGen gives a tet the attribute of the region seed it can reach without crossing a facet
// (volume/tetgen_mesher.h seeds every connected piece of every tissue's boundary). A surface with
// two triangles of one patch folded almost flat onto each other can enclose a cell that no piece's
// seed reaches: TetGen leaves its tets without attribute, and dropping them, as for a cavity of
// "outside" (an ignored label enclosed by tissue), would leave an unmeshed pocket inside a tissue
// that no conformity count sees. Each face-connected group of such tets (connected across faces
// that are not surface triangles) takes the region on its side of the surface triangles that bound
// it (a triangle labelled p|q has its normal from p into q): a group all of whose bounding
// triangles put it on one tissue's side becomes that tissue; one on the outside's side stays a
// cavity (id 0); a group with conflicting sides takes the side of the largest bounding area.
// Surface points are the mesh's first nodes, by index (as TetGen -Y keeps them). Deterministic.
#pragma once

#include "core/tet_mesh.h"
#include "core/tri_surface.h"

#include <cstddef>
#include <string>
#include <vector>

namespace tissuemesh {

struct UnseededCells {
  std::size_t tets = 0;       ///< tets without a region that were given a tissue
  double volume_mm3 = 0.0;    ///< their volume
  std::size_t groups = 0;     ///< face-connected groups of them
};

/// The warning that names what label_unseeded_cells did ("" when it gave no tet a tissue).
std::string unseeded_warning(const UnseededCells& u);

/// `ids[t]`: TetGen's region attribute of tet t (0: none); tets of `tets` over `points` (mm) are
/// positively oriented. Sets ids of unseeded tets as above; the rest stay. Requires the surface's
/// points to be the first points and points.size() < kMaxFaceKeyNodes (core/face_key.h).
UnseededCells label_unseeded_cells(const std::vector<Eigen::Vector3d>& points,
                                   const std::vector<std::array<int, 4>>& tets, const TriSurface& surface,
                                   std::vector<int>& ids);

}  // namespace tissuemesh
