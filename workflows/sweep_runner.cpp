#include "workflows/sweep_runner.h"

#include "core/errors.h"
#include "core/unit_system.h"
#include "solver_check/static_solver.h"
#include "workflows/reference_state.h"
#include "workflows/step_models.h"
#include "workflows/sweep_parameters.h"

#include <algorithm>
#include <atomic>
#include <exception>
#include <chrono>
#include <cmath>
#include <limits>
#include <mutex>
#include <thread>

namespace tissuemesh {

Model sample_model(const Model& base, const SweepSpec& spec, const SweepSample& sample) {
  Model m = base;
  for (std::size_t i = 0; i < spec.parameters.size(); ++i) apply_parameter(m, spec.parameters[i].path, sample.values[i]);
  validate_model(m);
  return m;
}

namespace {

/// One prone-to-supine sample: reference state, supine solve, prone-to-supine displacements.
void run_prone2supine(const Model& m, const SweepRunOptions& options, SampleOutcome& out) {
  const Prone2SupineSettings& p2s = options.prone2supine;
  const Model unloading = unloading_model(m, options.model_settings, p2s);
  const ReferenceStateResult ref =
      estimate_reference_state(unloading, reference_state_options(p2s, options.threads_per_job), {});
  int newton = ref.reversal.total_iterations, increments = static_cast<int>(ref.reversal.steps.size());
  for (const ReferenceIteration& it : ref.history) {
    newton += it.newton_iterations;
    increments += it.increments;
  }
  const Model supine = supine_model(m, options.model_settings, p2s, ref.reference_nodes);
  SolveOptions solve;
  solve.threads = options.threads_per_job;
  const SolveResult r = solve_static(supine, solve);
  out.newton_iterations = newton + r.total_iterations;
  out.increments = increments + static_cast<int>(r.steps.size());
  out.converged = ref.converged && r.converged;
  out.message = !ref.converged ? "reference state: " + ref.message
                               : "reference state " + ref.message + "; supine solve " + r.message;
  const double mm = 1.0 / length_from_mm(m.units, 1.0);
  out.displacements_mm.resize(m.nodes.size());
  std::vector<Eigen::Vector3d> from_prone(m.nodes.size());
  for (std::size_t v = 0; v < m.nodes.size(); ++v) {
    out.displacements_mm[v] = ref.reference_nodes[v] + r.displacements[v] * mm - unloading.nodes[v];
    from_prone[v] = out.displacements_mm[v] / mm;  // model length unit, as tissue_motion expects
  }
  if (!out.converged) {
    out.displacements_mm.clear();
    return;
  }
  const MotionSummary motion = tissue_motion(unloading, from_prone);
  out.max_displacement_mm = motion.max_displacement_mm;
  out.tissues = motion.tissues;
  const double weight = r.total_load.norm();
  out.reaction_vs_weight_rel = weight > 0.0 ? (r.total_reaction + r.load_fraction * r.total_load).norm() / weight : 0.0;
}

}  // namespace

int run_samples(const Model& base, const SweepSpec& spec, const std::vector<SweepSample>& design,
                const std::vector<int>& todo, SweepRunOptions options) {
  std::mutex lock;
  std::map<int, std::vector<Eigen::Vector3d>> fields = std::move(options.finished_fields);
  std::atomic<std::size_t> next{0};
  std::atomic<int> ran{0};
  const double per_mm = length_from_mm(base.units, 1.0);

  // The start of a sample: the nearest finished field among the warm_window samples before it.
  auto pick_start = [&](const SweepSample& s) -> int {
    if (!options.warm_start) return -1;
    int best = -1;
    double best_d = std::numeric_limits<double>::infinity();
    for (auto it = fields.lower_bound(s.index - options.warm_window); it != fields.end() && it->first < s.index; ++it) {
      if (it->first < 0 || it->first >= static_cast<int>(design.size())) continue;
      const std::vector<double>& u = design[it->first].unit;
      double d = 0.0;
      for (std::size_t k = 0; k < s.unit.size(); ++k) d += (s.unit[k] - u[k]) * (s.unit[k] - u[k]);
      if (d < best_d) {
        best_d = d;
        best = it->first;
      }
    }
    return best;
  };

  std::exception_ptr failure;  // the first error of on_finished (writing a sample): stops the sweep
  auto worker = [&] {
    SolverWorkspace workspace;
    for (;;) {
      if (options.should_stop && options.should_stop()) return;
      {
        std::lock_guard<std::mutex> g(lock);
        if (failure) return;
      }
      const std::size_t i = next++;
      if (i >= todo.size()) return;
      const SweepSample& s = design.at(todo[i]);
      const auto start = std::chrono::steady_clock::now();
      SampleOutcome out;
      out.index = s.index;
      try {
        const Model m = sample_model(base, spec, s);
        if (spec.analysis == "prone2supine") {
          run_prone2supine(m, options, out);
        } else {
          SolveOptions solve;
          solve.threads = options.threads_per_job;
          solve.workspace = &workspace;
          {
            std::lock_guard<std::mutex> g(lock);
            out.warm_from = pick_start(s);
            if (out.warm_from >= 0) {
              const std::vector<Eigen::Vector3d>& u = fields.at(out.warm_from);
              solve.initial_displacements.resize(u.size());
              for (std::size_t v = 0; v < u.size(); ++v) solve.initial_displacements[v] = u[v] * per_mm;
            }
          }
          workspace.forget_factorisation();
          const SolveResult r = solve_static(m, solve);
          out.converged = r.converged;
          out.message = r.message;
          out.increments = static_cast<int>(r.steps.size());
          out.newton_iterations = r.total_iterations;
          if (r.converged) {
            out.displacements_mm.resize(r.displacements.size());
            for (std::size_t v = 0; v < r.displacements.size(); ++v)
              out.displacements_mm[v] = r.displacements[v] / per_mm;
            const MotionSummary motion = tissue_motion(m, r.displacements);
            out.max_displacement_mm = motion.max_displacement_mm;
            out.tissues = motion.tissues;
            const double weight = r.total_load.norm();
            out.reaction_vs_weight_rel =
                weight > 0.0 ? (r.total_reaction + r.load_fraction * r.total_load).norm() / weight : 0.0;
          }
        }
      } catch (const std::exception& e) {  // a sample never stops the sweep: its row says why
        out = SampleOutcome();
        out.index = s.index;
        out.message = e.what();
      }
      out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      std::lock_guard<std::mutex> g(lock);
      if (failure) return;
      if (out.converged && options.warm_start) {
        fields[s.index] = out.displacements_mm;
        // Only the warm_window samples before the next one to start can still be chosen.
        const std::size_t upcoming = next.load();
        const int lowest = upcoming < todo.size() ? todo[upcoming] : std::numeric_limits<int>::max();
        fields.erase(fields.begin(), fields.lower_bound(lowest - options.warm_window - options.jobs));
      }
      try {
        if (options.on_finished) options.on_finished(s, out);
      } catch (...) {
        failure = std::current_exception();
        return;
      }
      ++ran;
    }
  };
  const int jobs = std::max(1, std::min<int>(options.jobs, static_cast<int>(todo.size())));
  if (jobs == 1) {
    worker();
  } else {
    std::vector<std::thread> threads;
    for (int j = 0; j < jobs; ++j) threads.emplace_back(worker);
    for (std::thread& t : threads) t.join();
  }
  if (failure) std::rethrow_exception(failure);
  return ran;
}

}  // namespace tissuemesh
