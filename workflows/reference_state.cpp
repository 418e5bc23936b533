#include "workflows/reference_state.h"

#include "core/errors.h"
#include "core/unit_system.h"
#include "workflows/anderson_mixing.h"

#include <algorithm>
#include <chrono>
#include <cmath>

namespace tissuemesh {

namespace {

using Clock = std::chrono::steady_clock;

/// Below this the relaxation is no longer making progress (UCL's loop has no floor; without one a
/// persistent failure would spend every remaining iteration on vanishing steps).
constexpr double kMinAlpha = 1e-3;

std::vector<Eigen::Vector3d> to_mm(const Model& model, const std::vector<Eigen::Vector3d>& u) {
  const double mm = 1.0 / length_from_mm(model.units, 1.0);
  std::vector<Eigen::Vector3d> out(u.size());
  for (std::size_t v = 0; v < u.size(); ++v) out[v] = u[v] * mm;
  return out;
}

std::vector<Eigen::Vector3d> from_mm(const Model& model, const std::vector<Eigen::Vector3d>& u_mm) {
  const double per_mm = length_from_mm(model.units, 1.0);
  std::vector<Eigen::Vector3d> out(u_mm.size());
  for (std::size_t v = 0; v < u_mm.size(); ++v) out[v] = u_mm[v] * per_mm;
  return out;
}

std::vector<Eigen::Vector3d> corners_of(const Model& model, const std::vector<Eigen::Vector3d>& all) {
  return {all.begin(), all.begin() + model.num_corner_nodes};
}

bool any_inverted(const Model& model) {
  for (std::size_t e = 0; e < model.elements.size(); ++e)
    if (!(element_volume(model, e) > 0.0)) return true;
  return false;
}

}  // namespace

Model with_corner_positions(const Model& model, const std::vector<Eigen::Vector3d>& corners) {
  Model m = model;
  std::copy(corners.begin(), corners.end(), m.nodes.begin());
  if (m.order == ElementOrder::Quadratic) {
    static const int kEdge[6][2] = {{0, 1}, {1, 2}, {2, 0}, {0, 3}, {1, 3}, {2, 3}};  // core/model.h
    for (const auto& el : m.elements)
      for (int k = 0; k < 6; ++k) m.nodes[el[4 + k]] = 0.5 * (m.nodes[el[kEdge[k][0]]] + m.nodes[el[kEdge[k][1]]]);
  }
  return m;
}

ReferenceStateResult estimate_reference_state(const Model& loaded, const ReferenceStateOptions& options,
                                              const std::function<void(const ReferenceIteration&)>& on_iteration) {
  const auto start = Clock::now();
  if (!(loaded.gravity.acceleration_m_s2.norm() > 0.0))
    throw InputError("the reference state needs the gravity the imaged shape carries (model.gravity is none)");
  ReferenceStateResult result;
  const int corners = loaded.num_corner_nodes;
  const std::vector<Eigen::Vector3d> x = corners_of(loaded, loaded.nodes);

  // Every solve has the same elements and constraints: one workspace for all.
  SolverWorkspace workspace;
  // Naive reversal: the imaged shape loaded by -g.
  SolveOptions reversed;
  reversed.gravity_scale = -1.0;
  reversed.threads = options.threads;
  reversed.workspace = &workspace;
  result.reversal = solve_static(loaded, reversed);
  std::vector<Eigen::Vector3d> X = x;
  std::vector<Eigen::Vector3d> start_u;  // warm start (mm) for the next solve; empty: from zero
  if (result.reversal.converged) {
    const std::vector<Eigen::Vector3d> u = to_mm(loaded, result.reversal.displacements);
    for (int v = 0; v < corners; ++v) X[v] = x[v] + u[v];
    // X_0 deformed by -u_rev is x again: where its forward solve starts.
    const std::vector<Eigen::Vector3d> X0 = with_corner_positions(loaded, X).nodes;
    start_u.resize(X0.size());
    for (std::size_t v = 0; v < X0.size(); ++v) start_u[v] = loaded.nodes[v] - X0[v];
  }
  // Not reversible (too soft for -g): start from the imaged shape itself.
  result.naive_nodes = with_corner_positions(loaded, X).nodes;

  SolveOptions forward;
  forward.threads = options.threads;
  forward.workspace = &workspace;
  double alpha = options.relaxation_initial;
  AndersonMixing mixing(options.anderson_memory);
  std::vector<Eigen::Vector3d> best_X, best_u;  // best iterate and its displacement (mm)
  Eigen::VectorXd best_f;                       // its fixed-point residual x - phi(X), flattened
  double best = INFINITY;
  std::string last_note;
  for (int k = 0; k < options.max_iterations; ++k) {
    ReferenceIteration it;
    it.index = k;
    it.alpha = k == 0 ? 0.0 : alpha;
    const Model model_k = with_corner_positions(loaded, X);
    if (any_inverted(model_k)) {
      it.note = "the update inverts an element";
    } else {
      if (!start_u.empty()) forward.initial_displacements = from_mm(loaded, start_u);
      const SolveResult r = solve_static(model_k, forward);
      it.solved = r.converged;
      it.newton_iterations = r.total_iterations;
      it.increments = static_cast<int>(r.steps.size());
      it.seconds = r.seconds;
      it.note = r.message;
      if (r.converged) {
        const std::vector<Eigen::Vector3d> u = to_mm(loaded, r.displacements);
        Eigen::VectorXd f(3 * corners);
        double mismatch = 0.0;
        for (int v = 0; v < corners; ++v) {
          const Eigen::Vector3d res = X[v] + u[v] - x[v];
          f.segment<3>(3 * v) = -res;
          mismatch = std::max(mismatch, res.norm());
        }
        it.mismatch_mm = mismatch;
        if (k == 0) {
          result.naive_measured = true;
          result.naive_mismatch_mm = mismatch;
        }
        if (mismatch < best) {
          it.improved = true;
          if (k > 0) alpha = std::min(1.0, alpha * options.relaxation_growth);
          best = mismatch;
          best_X = X;
          best_f = std::move(f);
          best_u = u;
          result.best_iteration = k;
        }
      }
    }
    if (!it.improved) {
      last_note = it.note;
      alpha *= options.relaxation_cut;
      mixing.restart();  // the rejected iterate's secant information is not trusted
      it.note = (it.solved ? "worse than the best iterate" : "rejected: " + it.note);
    }
    result.history.push_back(it);
    if (on_iteration) on_iteration(result.history.back());
    if (best <= options.tolerance_mm) {
      result.converged = true;
      break;
    }
    if (best_X.empty()) {  // nothing solved yet: no iterate to update from
      result.message = std::string(result.reversal.converged ? "" : "naive reversal did not converge (" +
                                                                        result.reversal.message + "); ") +
                       "the first forward solve under gravity failed: " + last_note;
      break;
    }
    if (alpha < kMinAlpha) {
      result.message = "stagnated: the relaxation fell below " + std::to_string(kMinAlpha) + " (last: " + last_note + ")";
      break;
    }
    // From the best iterate (the current one after an improvement): X_best - alpha r_best, with
    // Anderson's secant correction; the next solve starts where phi(X_{k+1}) = x would hold.
    Eigen::VectorXd flat(3 * corners);
    for (int v = 0; v < corners; ++v) flat.segment<3>(3 * v) = best_X[v];
    const Eigen::VectorXd next = mixing.next(flat, best_f, alpha);
    for (int v = 0; v < corners; ++v) X[v] = next.segment<3>(3 * v);
    const std::vector<Eigen::Vector3d> next_nodes = with_corner_positions(loaded, X).nodes;
    const std::vector<Eigen::Vector3d> best_nodes = with_corner_positions(loaded, best_X).nodes;
    start_u.resize(loaded.nodes.size());
    for (std::size_t v = 0; v < loaded.nodes.size(); ++v)
      start_u[v] = best_u[v] + best_nodes[v] - next_nodes[v];
  }
  if (!best_X.empty()) {
    result.measured = true;
    result.mismatch_mm = best;
    result.reference_nodes = with_corner_positions(loaded, best_X).nodes;
    result.loaded_displacements_mm = best_u;
  } else {
    result.reference_nodes = result.naive_nodes;
    result.loaded_displacements_mm.assign(loaded.nodes.size(), Eigen::Vector3d::Zero());
  }
  if (result.converged) {
    result.message = "converged: max nodal mismatch " + std::to_string(best) + " mm after " +
                     std::to_string(result.history.size()) + " forward solves";
  } else if (result.message.empty()) {
    result.message = "no convergence in " + std::to_string(options.max_iterations) +
                     " forward solves (best max nodal mismatch " +
                     (result.measured ? std::to_string(best) + " mm" : std::string("not measured")) + ")";
  }
  result.seconds = std::chrono::duration<double>(Clock::now() - start).count();
  return result;
}

}  // namespace tissuemesh
