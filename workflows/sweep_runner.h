// Running a sweep's samples on one model (docs/sweeps.md, "How samples run").
//
// Built once and shared: the model (mesh, sets, element data come with it), and per job one
// SolverWorkspace (the ordering and symbolic analysis of the tangent, computed by the job's first
// solve). Each sample: the base model with its parameter values applied (sweep_parameters.h), then
// solve_static under the model's gravity, starting from the displacement of the nearest finished
// sample (Euclidean distance of the unit coordinates; ties: the lower index) among the
// `warm_window` samples before it in design order, when warm starts are on. Before each solve the
// workspace forgets its kept factorisation, so a sample's result depends only on its model and its
// start: with one job a sweep gives the same bits whether it ran at once or was resumed (given the
// same finished fields). With several jobs the start of a sample depends on which samples finished
// first; results agree within the solver's tolerance.
// `jobs` samples run side by side on threads, each solve with `threads_per_job` assembly threads.
// A sample whose values make no physical material, whose solve does not converge, or that fails in
// any other way (std::exception) is an outcome with converged = false and the reason; it never
// stops the sweep. An exception thrown by `on_finished` (writing the sample) stops handing out
// samples and is rethrown by run_samples once the running ones have ended.
// With `analysis: prone2supine` each sample runs the prone-to-supine workflow instead
// (workflows/reference_state.h, step_models.h; `base` must then be built with settings_for_steps):
// the outcome's displacement is then the prone-to-supine one (supine minus prone position), the
// tissue figures its volume-mean over the prone shape, the reaction the supine solve's, the Newton
// iterations those of every solve, and converged both the reference state and the supine solve.
// Its solves warm-start inside the workflow, not from other samples.
#pragma once

#include "core/model.h"
#include "solver_check/tissue_motion.h"
#include "core/model_settings.h"
#include "workflows/prone2supine_settings.h"
#include "workflows/sweep_design.h"
#include "workflows/sweep_spec.h"

#include <Eigen/Core>

#include <functional>
#include <map>
#include <string>
#include <vector>

namespace tissuemesh {

struct SampleOutcome {
  int index = 0;
  bool converged = false;
  std::string message;               ///< the solver's, or why the sample could not run
  double max_displacement_mm = 0.0;
  std::vector<TissueMotion> tissues;  ///< per tissue: volume-mean displacement (mm) and more; empty unless converged
  double reaction_vs_weight_rel = 0.0;
  int increments = 0, newton_iterations = 0;
  double seconds = 0.0;               ///< wall time of the sample (model, solve, motion)
  int warm_from = -1;                 ///< the sample whose displacement started the solve (-1: cold)
  std::vector<Eigen::Vector3d> displacements_mm;  ///< per model node (empty unless converged)
};

struct SweepRunOptions {
  int jobs = 1;
  int threads_per_job = 1;
  bool warm_start = true;
  int warm_window = 64;
  /// Finished samples' displacements (mm, per model node) available as starts, by sample index
  /// (e.g. read back when a sweep resumes).
  std::map<int, std::vector<Eigen::Vector3d>> finished_fields;
  /// Called once per finished sample, one call at a time (under a lock), in completion order.
  std::function<void(const SweepSample&, const SampleOutcome&)> on_finished;
  /// Polled before each sample starts: true stops handing out samples (running ones finish).
  std::function<bool()> should_stop;
  /// analysis prone2supine: the model settings (for the sets a step does not name) and the workflow.
  ModelSettings model_settings;
  Prone2SupineSettings prone2supine;
};

/// The model of one sample: `base` with `sample`'s values applied. InputError with the reason for
/// values that make no physical material.
Model sample_model(const Model& base, const SweepSpec& spec, const SweepSample& sample);

/// Runs the samples of `design` (make_design) whose indices are in `todo` (ascending). Returns the
/// number run.
int run_samples(const Model& base, const SweepSpec& spec, const std::vector<SweepSample>& design,
                const std::vector<int>& todo, SweepRunOptions options);

}  // namespace tissuemesh
