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

/// The model of `mesh` with `config` (materials, model settings) as a "build model" stage: what
/// `export`, `solve`, `check` and `demo` all start from. Throws InputError when the config has no
/// `materials:` or the model refuses the mesh (build_model's errors).
Model build_job_model(const TetMesh& mesh, const JobConfig& config, Progress& progress);

/// The model of a mesh file, with what a run record says about its inputs.
struct JobModel {
  Model model;
  nlohmann::json inputs;  ///< {"mesh": ..., "config": ...}, absolute paths
};

/// Reads `mesh_path` (a .vtu of `tissuemesh mesh`) in a "read MESH" stage; InputError when it
/// cannot be read.
TetMesh read_job_mesh(const std::string& mesh_path, Progress& progress);

/// The run record's "inputs" of a job on a mesh file: {"mesh": ..., "config": ...}, absolute paths.
nlohmann::json job_inputs(const std::string& mesh_path, const JobConfig& config);

/// Where `export`, `solve` and `check` start: reads `mesh_path` (a .vtu of `tissuemesh mesh`) in a
/// "read MESH" stage, then build_job_model. Throws InputError for an unreadable mesh and what
/// build_job_model throws.
JobModel read_job_model(const std::string& mesh_path, const JobConfig& config, Progress& progress);

/// Writes every format of `formats` under its default name (model.feb, model.inp, model.scn +
/// model.vtk, model.vtu, model.msh) into `out`'s staging folder, and stages export.json (the run
/// record: inputs, effective config, versions, timings, model counts, total weight, files, notes)
/// and prints a summary. Throws InputError before writing anything when a format refuses the
/// model. Does not commit `out`. Returns the record.
nlohmann::json export_into(const Model& model, const JobConfig& config, const std::vector<std::string>& formats,
                           const nlohmann::json& inputs, const std::string& command_line, Progress& progress,
                           OutputDir& out);

/// Counts and physical totals of a model, for records and the console (units stated in keys).
nlohmann::json model_summary_json(const Model& model);

}  // namespace tissuemesh::app
