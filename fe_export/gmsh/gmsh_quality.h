// Element quality of a tet mesh as the Gmsh SDK computes it: an independent check of our own
// shape measures (quality/mesh_quality.h) by the code many users judge meshes with.
//
// The mesh goes to Gmsh as one discrete volume (nodes and linear tets in mesh order), and Gmsh
// writes its mesh statistics as a post-processing view (options Print.PostSICN and
// Print.PostGamma, `.pos` format) to `pos_path`; that file is read back. Per tet:
//   gamma: 3 * inradius / circumradius (1 regular, 0 degenerate, unsigned);
//   SICN:  signed inverse condition number of the map from the regular tet (1 regular, < 0
//          inverted).
// Gmsh 4.8 prints 6 significant digits ("%g"), which bounds any agreement check. The file opens
// in Gmsh as the view "Statistics". Coordinates in mm (the measures are scale-free).
#pragma once

#include "core/tet_mesh.h"

#include <string>
#include <vector>

namespace tissuemesh {

struct GmshTetQuality {
  double gamma = 0;
  double sicn = 0;
};

struct GmshQuality {
  std::string version;               ///< Gmsh's General.Version, e.g. "4.8.4"
  std::vector<GmshTetQuality> tets;  ///< per tet of the mesh, in tet order
};

/// Gmsh's quality of every tet of `mesh`. Writes `pos_path` (Gmsh's statistics view). Throws
/// OutputError naming pos_path when Gmsh cannot write it or the file does not hold one
/// gamma/SICN record per tet at the tet's own node coordinates. Not thread-safe (Gmsh is global
/// state).
GmshQuality gmsh_tet_quality(const TetMesh& mesh, const std::string& pos_path);

}  // namespace tissuemesh
