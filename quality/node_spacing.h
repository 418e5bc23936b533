// The local tet size of a mesh at its nodes: for every node, the largest circumradius of the tets
// that contain it (mm), the measure CGAL's and TetGen's cell size criteria bound. `check --tetgen`
// gives these to TetGen at the surface nodes (volume/tetgen_mesher.h, switch m), so the
// cross-check mesh may have tets as large as the checked mesh has there and no larger: both have
// the same resolution, wherever that mesh is fine or coarse. Nodes in no tet, or only in flat
// ones (infinite circumradius), get 0. Deterministic.
#pragma once

#include "core/tet_mesh.h"

#include <vector>

namespace tissuemesh {

std::vector<double> largest_incident_circumradius_mm(const TetMesh& mesh);

}  // namespace tissuemesh
