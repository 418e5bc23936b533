// The model as a Gmsh mesh (.msh 4.1, ASCII) written through the Gmsh SDK: one discrete volume
// entity and one physical group (dim 3, named after the tissue) per tissue; per node set a
// physical group of dim 0 over one point entity per node; per face set a discrete surface with
// its triangles (tri3/tri6) and a physical group (dim 2). Node tags are the model's 1-based
// indices; tet4 is element type 4, tet10 type 11 (Gmsh's tet10 node order differs from VTK's in
// the last two nodes: 9 <-> 10, handled here). Coordinates in mm.
#pragma once

#include "core/model.h"

#include <string>

namespace tissuemesh {

/// Throws OutputError naming the path on failure. Not thread-safe (the Gmsh SDK is global state).
void write_gmsh(const Model& model, const std::string& path);

}  // namespace tissuemesh
