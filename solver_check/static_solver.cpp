#include "solver_check/static_solver.h"

#include "core/errors.h"
#include "materials/make_law.h"
#include "solver_check/element_kernel.h"

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <sstream>

namespace tissuemesh {
namespace {

using SparseMatrix = Eigen::SparseMatrix<double>;

/// Everything fixed for the whole solve: reference geometry, laws, dof numbering, load.
struct Problem {
  ElementOrder order = ElementOrder::Linear;
  int nodes_per_element = 4;
  std::vector<ElementNodes> X;                         ///< per element, model length unit
  std::vector<const HyperelasticLaw*> law;             ///< per element
  std::vector<std::unique_ptr<HyperelasticLaw>> laws;  ///< per tissue
  std::vector<std::array<int, 10>> elements;
  int num_dofs = 0;
  std::vector<int> free_index;   ///< per global dof: index among free dofs, or -1 (fixed)
  std::vector<int> free_dofs;    ///< free index -> global dof
  std::vector<int> fixed_nodes;  ///< sorted, unique
  Eigen::VectorXd f_ext;         ///< global, lambda = 1
};

/// Global internal force (all dofs) and, optionally, the free-dof tangent (lower triangle).
struct Assembly {
  bool ok = true;
  std::string note;
  Eigen::VectorXd f_int;
  SparseMatrix K;
};

void check_model(const Model& model) {
  validate_model(model);
  bool has_fixed = false;
  for (const NodeSet& set : model.node_sets) {
    if (set.constraint == Constraint::Sliding)
      throw SolverError("node set '" + set.name +
                        "': sliding (normal-only) constraints are not supported yet by the built-in solver");
    if (set.constraint == Constraint::Fixed && !set.nodes.empty()) has_fixed = true;
  }
  if (!has_fixed)
    throw InputError("model '" + model.title +
                     "' has no fixed node set: it is not held in place and cannot be solved statically");
  for (std::size_t t = 0; t < model.materials.size(); ++t)
    if (!(model.materials[t].density_kg_m3 > 0.0))
      throw InputError("tissue '" + model.tissue_names.at(t) + "' has density " +
                       std::to_string(model.materials[t].density_kg_m3) +
                       " kg/m^3: every tissue needs a positive density for a gravity solve");
}

Problem build_problem(const Model& model, const SolveOptions& options) {
  Problem p;
  p.order = model.order;
  p.nodes_per_element = model.nodes_per_element();
  p.elements = model.elements;
  const UnitSystem units = model.units;
  for (const MaterialSpec& spec : model.materials) p.laws.push_back(make_law(spec, units));

  Eigen::Vector3d g;
  for (int i = 0; i < 3; ++i)
    g[i] = acceleration_from_m_per_s2(units, model.gravity.acceleration_m_s2[i]) * options.gravity_scale;

  const int n = p.nodes_per_element;
  p.num_dofs = 3 * static_cast<int>(model.nodes.size());
  p.f_ext = Eigen::VectorXd::Zero(p.num_dofs);
  p.X.resize(model.elements.size());
  p.law.resize(model.elements.size());
  for (std::size_t e = 0; e < model.elements.size(); ++e) {
    ElementNodes X(n, 3);
    for (int a = 0; a < n; ++a)
      for (int i = 0; i < 3; ++i) X(a, i) = length_from_mm(units, model.nodes[model.elements[e][a]][i]);
    p.X[e] = X;
    const int tissue = model.tissue_ids[e] - 1;
    p.law[e] = p.laws.at(tissue).get();
    const double rho = density_from_kg_per_m3(units, model.materials[tissue].density_kg_m3);
    const ElementVector fb = element_body_force(p.order, X, rho, g);  // throws on inverted reference
    for (int a = 0; a < n; ++a)
      for (int i = 0; i < 3; ++i) p.f_ext[3 * model.elements[e][a] + i] += fb[3 * a + i];
  }

  std::vector<char> fixed(model.nodes.size(), 0);
  for (const NodeSet& set : model.node_sets)
    if (set.constraint == Constraint::Fixed)
      for (int v : set.nodes) fixed[v] = 1;
  p.free_index.assign(p.num_dofs, -1);
  for (std::size_t v = 0; v < model.nodes.size(); ++v) {
    if (fixed[v]) {
      p.fixed_nodes.push_back(static_cast<int>(v));
      continue;
    }
    for (int i = 0; i < 3; ++i) {
      p.free_index[3 * v + i] = static_cast<int>(p.free_dofs.size());
      p.free_dofs.push_back(static_cast<int>(3 * v + i));
    }
  }
  return p;
}

/// u_full: global displacement vector. Serial, element order: deterministic.
Assembly assemble(const Problem& p, const Eigen::VectorXd& u_full, bool with_tangent) {
  Assembly out;
  out.f_int = Eigen::VectorXd::Zero(p.num_dofs);
  const int n = p.nodes_per_element;
  std::vector<Eigen::Triplet<double>> triplets;
  if (with_tangent) triplets.reserve(p.elements.size() * (3 * n) * (3 * n + 1) / 2);
  ElementNodes u(n, 3);
  int dof[30];
  for (std::size_t e = 0; e < p.elements.size(); ++e) {
    for (int a = 0; a < n; ++a) {
      const int v = p.elements[e][a];
      for (int i = 0; i < 3; ++i) {
        u(a, i) = u_full[3 * v + i];
        dof[3 * a + i] = 3 * v + i;
      }
    }
    const ElementResponse r = element_response(
        p.order, p.X[e], u, *p.law[e],
        with_tangent ? ElementOutput::EnergyForceAndTangent : ElementOutput::EnergyAndForce);
    if (!r.ok()) {
      if (r.status == ElementStatus::InvertedReference)
        throw SolverError("element " + std::to_string(e) + " is inverted or flat in the reference configuration");
      out.ok = false;
      std::ostringstream note;
      note << (r.status == ElementStatus::Inverted ? "inverted element " : "non-finite response in element ") << e
           << " (min J " << r.min_J << ")";
      out.note = note.str();
      return out;
    }
    for (int k = 0; k < 3 * n; ++k) out.f_int[dof[k]] += r.force[k];
    if (!with_tangent) continue;
    for (int c = 0; c < 3 * n; ++c) {
      const int fc = p.free_index[dof[c]];
      if (fc < 0) continue;
      for (int rr = 0; rr < 3 * n; ++rr) {
        const int fr = p.free_index[dof[rr]];
        if (fr >= fc) triplets.emplace_back(fr, fc, r.tangent(rr, c));
      }
    }
  }
  if (with_tangent) {
    const int nf = static_cast<int>(p.free_dofs.size());
    out.K.resize(nf, nf);
    out.K.setFromTriplets(triplets.begin(), triplets.end());
  }
  return out;
}

Eigen::VectorXd free_part(const Problem& p, const Eigen::VectorXd& full) {
  Eigen::VectorXd out(p.free_dofs.size());
  for (std::size_t k = 0; k < p.free_dofs.size(); ++k) out[k] = full[p.free_dofs[k]];
  return out;
}

bool finite(const Eigen::VectorXd& v) { return v.allFinite(); }

/// The linear solver with its symbolic factorisation kept across iterations.
struct LinearSolver {
  Eigen::SimplicialLDLT<SparseMatrix, Eigen::Lower> ldlt;
  bool analysed = false;
  bool solve(const SparseMatrix& K, const Eigen::VectorXd& rhs, Eigen::VectorXd& x) {
    if (!analysed) {
      ldlt.analyzePattern(K);
      analysed = true;
    }
    ldlt.factorize(K);
    if (ldlt.info() != Eigen::Success) return false;
    x = ldlt.solve(rhs);
    return ldlt.info() == Eigen::Success && finite(x);
  }
};

/// One load increment: Newton from u (global) to lambda. On success u holds the new state.
bool newton_increment(const Problem& p, const AnalysisSettings& s, LinearSolver& linear, double lambda,
                      Eigen::VectorXd& u, StepRecord& record) {
  Eigen::VectorXd trial = u;
  const Eigen::VectorXd f_free = lambda * free_part(p, p.f_ext);
  const double ref = f_free.norm() > 0.0 ? f_free.norm() : 1.0;
  Assembly current = assemble(p, trial, true);
  if (!current.ok) {
    record.note = current.note;
    return false;
  }
  Eigen::VectorXd R = f_free - free_part(p, current.f_int);
  double rnorm = R.norm();
  record.residual_norms.push_back(rnorm / ref);
  if (!std::isfinite(rnorm)) {
    record.note = "non-finite residual";
    return false;
  }
  if (rnorm <= s.residual_tolerance * ref && f_free.norm() == 0.0) {
    u = trial;  // nothing to do (no load)
    return true;
  }
  for (int it = 1; it <= s.max_newton_iterations; ++it) {
    record.iterations = it;
    Eigen::VectorXd du;
    if (!linear.solve(current.K, R, du)) {
      record.note = "linear solve failed (singular or non-finite tangent)";
      return false;
    }
    // Backtracking line search on ||R||.
    double best_norm = INFINITY, best_alpha = 0.0;
    Assembly best;
    Eigen::VectorXd best_R, best_u;
    std::string inverted_note;
    for (double alpha = 1.0; alpha >= 1.0 / 16.0; alpha *= 0.5) {
      Eigen::VectorXd candidate = trial;
      for (std::size_t k = 0; k < p.free_dofs.size(); ++k) candidate[p.free_dofs[k]] += alpha * du[k];
      Assembly a = assemble(p, candidate, true);
      if (!a.ok) {
        inverted_note = a.note;
        continue;
      }
      Eigen::VectorXd Ra = f_free - free_part(p, a.f_int);
      const double na = Ra.norm();
      if (!std::isfinite(na)) continue;
      if (na < best_norm) {
        best_norm = na;
        best_alpha = alpha;
        best = std::move(a);
        best_R = std::move(Ra);
        best_u = std::move(candidate);
      }
      if (na < rnorm) break;
    }
    if (best_alpha == 0.0) {
      record.note = inverted_note.empty() ? "non-finite residual" : inverted_note;
      return false;
    }
    trial = std::move(best_u);
    current = std::move(best);
    R = std::move(best_R);
    rnorm = best_norm;
    record.residual_norms.push_back(rnorm / ref);
    const double du_norm = best_alpha * du.norm();
    const double u_norm = free_part(p, trial).norm();
    if (rnorm <= s.residual_tolerance * ref && du_norm <= s.displacement_tolerance * u_norm) {
      u = trial;
      return true;
    }
    if (rnorm > 1e12 * ref) {
      record.note = "diverged (residual grew beyond 1e12 of the load)";
      return false;
    }
  }
  record.note = "no convergence in " + std::to_string(s.max_newton_iterations) + " Newton iterations";
  return false;
}

}  // namespace

SolveResult solve_static(const Model& model, const SolveOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  check_model(model);
  if (!std::isfinite(options.gravity_scale)) throw InputError("gravity scale must be finite");
  const Problem p = build_problem(model, options);
  const AnalysisSettings& s = model.analysis;
  if (s.load_steps < 1 || s.max_newton_iterations < 1 || !(s.min_step_fraction > 0.0) || s.max_load_steps < 1)
    throw InputError("analysis settings: load_steps, max_newton_iterations, max_load_steps and min_step_fraction must be positive");

  SolveResult result;
  Eigen::VectorXd u = Eigen::VectorXd::Zero(p.num_dofs);
  LinearSolver linear;
  const double initial = 1.0 / s.load_steps;
  double lambda = 0.0, increment = initial;
  int successes = 0;
  bool failed = false;
  while (lambda < 1.0) {
    if (static_cast<int>(result.steps.size()) >= s.max_load_steps) {
      result.message = "stopped after " + std::to_string(s.max_load_steps) + " load increments (max_load_steps) at load fraction " +
                       std::to_string(lambda);
      failed = true;
      break;
    }
    StepRecord record;
    const double target = (1.0 - lambda <= increment * (1.0 + 1e-9)) ? 1.0 : lambda + increment;
    record.load_fraction = target;
    record.increment = target - lambda;
    Eigen::VectorXd attempt = u;
    const bool ok = newton_increment(p, s, linear, target, attempt, record);
    result.total_iterations += record.iterations;
    record.accepted = ok;
    if (ok) {
      u = std::move(attempt);
      lambda = target;
      if (++successes >= 2 && increment < initial) {
        increment = std::min(initial, 2.0 * increment);
        successes = 0;
      }
      result.steps.push_back(std::move(record));
      continue;
    }
    successes = 0;
    const std::string note = record.note;
    result.steps.push_back(std::move(record));
    increment *= 0.5;
    if (increment < s.min_step_fraction * (1.0 - 1e-12)) {
      result.message = "load increment fell below min_step_fraction " + std::to_string(s.min_step_fraction) +
                       " at load fraction " + std::to_string(lambda) + " (last failure: " + note + ")";
      failed = true;
      break;
    }
  }

  // Output: last accepted state (finite by construction: only finite states are accepted).
  result.converged = !failed;
  result.load_fraction = lambda;
  result.displacements.resize(model.nodes.size());
  for (std::size_t v = 0; v < model.nodes.size(); ++v)
    result.displacements[v] = u.segment<3>(3 * v);  // already in the model's length unit
  for (std::size_t v = 0; v < model.nodes.size(); ++v) result.total_load += p.f_ext.segment<3>(3 * v);
  const Assembly final_state = assemble(p, u, false);
  if (final_state.ok) {
    for (int v : p.fixed_nodes) {
      NodeReaction r;
      r.node = v;
      r.force = final_state.f_int.segment<3>(3 * v) - lambda * p.f_ext.segment<3>(3 * v);
      result.total_reaction += r.force;
      result.reactions.push_back(r);
    }
  }
  if (result.converged) {
    std::ostringstream msg;
    msg << "converged: " << result.steps.size() << " increments, " << result.total_iterations
        << " Newton iterations";
    result.message = msg.str();
  }
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace tissuemesh
