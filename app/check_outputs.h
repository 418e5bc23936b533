// The CalculiX cross-check: the same model solved by CalculiX (ccx) and by the built-in solver,
// displacements compared node by node (docs/verification.md, "Solver: agreement with CalculiX").
// Shared by `check --calculix` and `demo`.
#pragma once

#include "app/html_outputs.h"
#include "app/job_config.h"
#include "core/model.h"
#include "core/output_dir.h"
#include "core/progress.h"
#include "solver_check/solution_comparison.h"
#include "solver_check/static_solver.h"

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace tissuemesh::app {

/// Path of ccx ($TISSUEMESH_CCX, else on PATH). Throws InputError saying how to get one (Debian
/// package `calculix-ccx`, or TISSUEMESH_CCX=/path/to/ccx) when there is none: called before any
/// long work so that a run does not mesh and solve for minutes and then fail. `alternative`, when
/// not empty, is offered as a third way out (e.g. "run the demo with --skip-calculix").
std::string require_calculix(const std::string& alternative = "");

/// The model both solvers solve: `model` with every CompressibleNeoHookean tissue replaced by
/// the uncoupled neo-Hookean that CalculiX has exactly (NEO HOOKE: MaterialLaw::NeoHookean,
/// C10 = mu/2, same mu, K and density). The two energies share mu and K at small strain but not
/// beyond it, so the check is of the solvers, not of the compressible law. NeoHookean,
/// MooneyRivlin and Ogden are CalculiX laws and stay. Appends one note per replaced tissue.
Model calculix_comparable_model(const Model& model, std::vector<std::string>& notes);

/// The built-in solve of `model` (default SolveOptions) as a "built-in solve" stage with one note
/// per increment; never throws for non-convergence (see SolveResult::converged).
SolveResult solve_builtin(const Model& model, Progress& progress);

/// What the check measured (the record holds it all; these are for the caller's summary).
struct CalculixCheck {
  nlohmann::json record;             ///< check.json
  bool builtin_converged = false;    ///< false: the comparison is of the last accepted increment
  std::string builtin_message;       ///< the built-in solve's summary or reason for failure
  SolutionComparison comparison;     ///< built-in against CalculiX (the reference), model length unit
  double calculix_seconds = 0.0;
  double builtin_seconds = 0.0;
};

/// Runs the check of `model` into `out`: stages calculix/model.inp (the deck of the comparable
/// model), solves the comparable model with solve_static, runs ccx on the deck in the staging
/// folder with 2 threads and stages every file ccx writes there (model.dat, .sta, .cvg, .frd,
/// .log, ...), reads the last displacements of NALL from model.dat, compares the two fields and stages
/// check.json (run record, inputs, config, model summary, calculix, builtin, comparison,
/// equilibrium, notes); prints a summary table. Does not commit `out`.
///
/// `solved`, when given, is the built-in result of `model` itself: it is reused when the
/// comparable model is `model` unchanged (no tissue replaced) instead of solving again.
///
/// Throws InputError when ccx is not found or the model cannot be written as a deck,
/// SolverError when ccx fails (exit code and the tail of its log) or stops before the end of the
/// step. A built-in solve that does not converge is not an exception: builtin_converged = false.
/// The comparison table goes into `report` (report.html) when given.
CalculixCheck calculix_check_into(const Model& model, const JobConfig& job, const nlohmann::json& inputs,
                                  const std::string& command_line, Progress& progress, OutputDir& out,
                                  const SolveResult* solved = nullptr, RunReport* report = nullptr);

}  // namespace tissuemesh::app
