// The TetGen cross-check (docs/verification.md, "Cross-check with TetGen"): the geometry of a tet
// mesh meshed again by TetGen, and the two meshes compared. Used by `check --tetgen`.
//
// The multi-material surface of MESH (every boundary and interface face once, with its two
// regions; quality/mesh_interfaces.h) goes to the TetGen backend (volume/tetgen_mesher.h, the
// config's `tetgen:` keys) with the input faces kept, so both meshes bound the same tissues with
// the same triangles. Compared per tissue: volumes, tets, nodes, dihedral statistics; per
// interface: areas; the radius-edge ratio against the configured bound and against the bound the
// input triangles force (volume/forced_radius_edge.h); and, with the config's model solved on
// each mesh by the built-in solver under gravity, the volume-mean displacement of the target
// tissue.
#pragma once

#include "app/job_config.h"
#include "core/output_dir.h"
#include "core/progress.h"
#include "core/tet_mesh.h"

#include <nlohmann/json.hpp>

#include <string>

namespace tissuemesh::app {

struct TetgenCheck {
  nlohmann::json record;           ///< check.json
  double max_volume_difference_percent = 0.0;  ///< over tissues, TetGen against MESH
  double target_displacement_difference_percent = 0.0;  ///< |d_tetgen - d_mesh| / |d_mesh|
  bool both_converged = false;
};

/// Runs the check into `out`: stages DIR/mesh_tetgen.vtu (the TetGen mesh, the same cell data as
/// mesh.vtu) and DIR/check.json, prints the comparison. `target` names the tissue whose
/// displacement is compared. Throws InputError for an unknown target or a config without
/// materials, MeshingError when TetGen fails. Does not commit `out`.
TetgenCheck tetgen_check_into(const TetMesh& mesh, const std::string& target, const JobConfig& config,
                              const nlohmann::json& inputs, const std::string& command_line, Progress& progress,
                              OutputDir& out);

}  // namespace tissuemesh::app
