// The Gmsh quality cross-check: our own element shape measures (quality/mesh_quality.h)
// against the Gmsh SDK's on the same mesh. Used by `check --gmsh`.
//
// Per tet, Gmsh's gamma is compared with our radius ratio 3r/R and Gmsh's SICN with ours; per
// tissue, the minimum and mean of each by both codes, next to our dihedral range (Gmsh reports no
// dihedral angles). Gmsh prints 6 significant digits, so agreement means a largest per-tet
// difference of about 1e-6; `agree` uses kGmshPrintedDigitsAbs.
#pragma once

#include "core/output_dir.h"
#include "core/progress.h"
#include "core/tet_mesh.h"

#include <nlohmann/json.hpp>

#include <string>

namespace tissuemesh::app {

/// Half a unit in the 6th significant digit of a value in [-1, 1] that Gmsh's "%g" printed,
/// plus round-off: the largest difference a correct pair of implementations can show.
inline constexpr double kGmshPrintedDigitsAbs = 1e-6;

struct GmshCheck {
  nlohmann::json record;           ///< check.json
  double max_gamma_difference = 0;  ///< over tets, |gamma_gmsh - radius_ratio_ours|
  double max_sicn_difference = 0;   ///< over tets, |SICN_gmsh - SICN_ours|
  bool agree = false;               ///< both maxima <= kGmshPrintedDigitsAbs
};

/// Runs the check into `out`: stages DIR/quality_gmsh.pos (Gmsh's statistics view: gamma and
/// SICN per tet; opens in Gmsh) and DIR/check.json, prints the comparison. Throws OutputError
/// when Gmsh fails. Does not commit `out`.
GmshCheck gmsh_check_into(const TetMesh& mesh, const nlohmann::json& inputs, const nlohmann::json& config_record,
                          const std::string& command_line, Progress& progress, OutputDir& out);

}  // namespace tissuemesh::app
