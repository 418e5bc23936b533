// Turning a mesh into a model and writing it in several formats: shared by `export` and `demo`.
#pragma once

#include "app/job_config.h"
#include "core/model.h"
#include "core/output_dir.h"
#include "core/progress.h"
#include "core/tet_mesh.h"

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace tissuemesh::app {

/// Builds the model of `mesh` with `config` (materials, model settings), writes every format of
/// `formats` under its default name (model.feb, model.inp, model.scn + model.vtk, model.vtu,
/// model.msh) into `out`'s staging folder, and stages export.json (the run record: inputs,
/// effective config, versions, timings, model counts, total weight, files, notes) and prints a
/// summary. Throws InputError before writing anything when the model or a format refuses it.
/// Does not commit `out`. Returns the record.
nlohmann::json export_into(const TetMesh& mesh, const JobConfig& config, const std::vector<std::string>& formats,
                           const nlohmann::json& inputs, const std::string& command_line, Progress& progress,
                           OutputDir& out);

/// Counts and physical totals of a model, for records and the console (units stated in keys).
nlohmann::json model_summary_json(const Model& model);

}  // namespace tissuemesh::app
