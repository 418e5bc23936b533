// Solving a model with the built-in solver into an output folder: shared by `solve` and `demo`.
// The files (docs/formats.md, "VTU"; docs/solver.md, "Outputs"):
//
// DIR/solution.vtu — the model VTU (write_model_vtu: same points in the same order as model.vtu
//   and the node ids of model.inp / model.feb minus 1, same cells, tissue_id, material arrays,
//   node-set flags) plus
//     point data  displacement     3 components, mm (converted from the model's length unit)
//     cell data   cauchy_stress    6 components xx, yy, zz, xy, yz, xz, Pa (solver_check/cell_fields.h)
//                 von_mises_stress Pa
//                 J                det F, volume mean over the element
//     field data  load_fraction (reached), displacement_unit "mm", stress_unit "Pa",
//                 solver_converged "true"/"false", solver_message.
// DIR/solve.json — run_record_common + inputs + config (source, effective yaml) + model
//   (model_summary_json) + units + solver (linear solver, threads, free dofs, converged, message,
//   load fraction, iterations, seconds, every attempted increment) + results (max displacement
//   and its 1-based node id, per-tissue volume-mean displacement, peak von Mises, J range, total
//   reaction and weight in N and their relative imbalance) + outputs.
#pragma once

#include "app/html_outputs.h"
#include "app/job_config.h"
#include "core/model.h"
#include "core/output_dir.h"
#include "core/progress.h"
#include "solver_check/static_solver.h"

#include <nlohmann/json.hpp>

#include <string>

namespace tissuemesh::app {

/// One progress line per attempted load increment, numbered from 1 by `attempt`:
/// "increment 3: load 0.3 (+0.1), 2 iterations, residual 3.1e-09, accepted, 0.04 s".
std::string step_line(const StepRecord& s, int attempt);

/// The solver part of a run record: linear solver, formulation, threads, convergence, every
/// attempted increment, counts and times (solve.json's "solver").
nlohmann::json solver_json(const SolveResult& r);

/// Throws std::logic_error naming the place when `j` holds a non-finite number (a solver bug:
/// nlohmann would write it as null). Call before writing a record.
void require_finite(const nlohmann::json& j, const std::string& where);

/// Solves `model` under its gravity with solve_static (settings: model.analysis) in a progress
/// stage "solve (built-in, <tet4|tet10>, N dofs)" with one note per attempted load increment,
/// stages DIR/solution.vtu and DIR/solve.json (header comment) into `out`, prints a summary and
/// returns the record (solve.json's content). Does not commit `out`. The displacement and the
/// residual history go into `report` (report.html) when given. When `result` is given it
/// receives the solver's result (e.g. for a CalculiX check of the same solve). `threads`: assembly
/// threads (0 = $OMP_NUM_THREADS, else all processors).
///
/// A solve that does not converge is not an exception: both files are staged with the last
/// accepted state (record["solver"]["converged"] false, the reason in ["message"], the load fraction
/// reached in the file and the record); the caller decides what to do (`solve` commits and exits 1).
/// Throws, before anything is staged, what solve_static refuses up front (InputError: no
/// constraint, a tissue without density, an invalid model; SolverError: an inverted reference
/// element), and std::logic_error when a result is not finite (a solver bug; nothing is written).
nlohmann::json solve_into(const Model& model, const JobConfig& config, const nlohmann::json& inputs,
                          const std::string& command_line, Progress& progress, OutputDir& out,
                          SolveResult* result = nullptr, int threads = 0, RunReport* report = nullptr);

}  // namespace tissuemesh::app
