// The prone-to-supine workflow into an output folder: shared by `prone2supine` and `demo
// --prone2supine` (docs/prone-to-supine.md, "Outputs"). All files are staged; the caller commits.
//
// DIR/reference.vtu      the unloaded reference: the input mesh (same points, order and cells as
//                        MESH) at the estimated reference positions — a mesh every command reads
// DIR/supine.vtu         the model VTU (model node order, as solution.vtu) at the supine positions;
//                        point data displacement_from_prone and displacement_from_reference (mm)
// DIR/prone_check.vtu    the reference loaded prone again (model VTU at those positions); point data
//                        displacement (from the reference, mm) and mismatch (to the input, mm)
// DIR/supine_model.feb, .inp, .scn (+ .vtk)
//                        the supine step on the reference geometry for FEBio, Abaqus/CalculiX, SOFA
// DIR/points.csv         with --points: each landmark's prone, reference and supine position (mm)
// DIR/supine_labels.nii.gz  with --image: the prone labels carried into the supine shape
// DIR/prone2supine.json  the run record: iteration history, naive reversal, per-tissue volumes and
//                        centroids in the three configurations, landmarks, files, timings
#pragma once

#include "app/html_outputs.h"
#include "app/job_config.h"
#include "core/output_dir.h"
#include "core/progress.h"
#include "core/tet_mesh.h"

#include <nlohmann/json.hpp>

#include <string>

namespace tissuemesh::app {

struct Prone2SupineRequest {
  std::string points_path;  ///< --points (empty: none)
  std::string image_path;   ///< --image (empty: none)
  int threads = 0;          ///< assembly threads
};

struct Prone2SupineOutcome {
  nlohmann::json record;   ///< prone2supine.json's content
  bool converged = false;  ///< the reference state met its tolerance and the supine solve converged
  std::string failure;     ///< why not (empty when converged)
};

/// Builds the model of `mesh` (the imaged, prone shape) with `config`, estimates the reference
/// state, solves the supine step and stages every file above into `out`, printing progress and a
/// summary. A run that does not converge still stages every file (the best iterate; the record
/// says why) and returns converged = false. Throws InputError before any solve for a bad config
/// (unknown node set, no gravity), a bad landmark file or a landmark outside the mesh, an
/// unreadable image; what build_model and solve_static refuse up front; InputError when a format
/// cannot represent the supine model (nothing committed). The shapes and the iteration history go
/// into `report` (report.html) when given.
Prone2SupineOutcome prone2supine_into(const TetMesh& mesh, const JobConfig& config, const Prone2SupineRequest& request,
                                      const nlohmann::json& inputs, const std::string& command_line,
                                      Progress& progress, OutputDir& out, RunReport* report = nullptr);

}  // namespace tissuemesh::app
