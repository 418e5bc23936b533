#include "solver_check/static_solver.h"

#include "core/errors.h"
#include "materials/make_law.h"
#include "materials/volumetric_split.h"
#include "solver_check/dof_map.h"
#include "solver_check/element_kernel.h"
#include "solver_check/linear_solver.h"
#include "solver_check/nodal_pressure.h"
#include "solver_check/reduced_assembly.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <sstream>
#include <stdexcept>

namespace tissuemesh {
namespace {

using Clock = std::chrono::steady_clock;

/// An increment that converged in at most kEasyIterations Newton iterations doubles the next one,
/// in at most kQuickIterations quadruples it: the load path is then nearly linear at this scale
/// (quadratic convergence from a good predictor takes 2-3 iterations), so a larger step costs
/// fewer Newton iterations and factorisations overall. On the phantom models, quadrupling after
/// at most 3 iterations instead of doubling saves up to a third of the Newton iterations and
/// factorisations and never costs any. Right after a cut-back an increment grows at most back to
/// the size that failed (doubling), so that failures and cut-backs do not alternate.
constexpr int kEasyIterations = 4;
constexpr int kQuickIterations = 3;

/// Relative accuracy of each Newton direction, ||K dq - R|| <= eta ||R||, when the linear solver
/// iterates on an old factorisation (an inexact Newton method): the forcing term
/// eta = ||R|| / scale, clamped to [kMinForcing, kMaxForcing] (Dembo, Eisenstat & Steihaug's
/// eta_k = O(||R_k||), which keeps Newton's quadratic convergence). Far from equilibrium a rough
/// direction does as well as an exact one, near it the solves tighten: the same Newton
/// iterations as a constant eta = kMinForcing, with about a third fewer CG iterations.
constexpr double kMinForcing = 1e-4;
constexpr double kMaxForcing = 1e-2;

double seconds_since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

/// Everything fixed for the whole solve: reference geometry, laws, load.
struct Problem {
  std::vector<std::unique_ptr<HyperelasticLaw>> laws;  ///< per tissue
  std::vector<std::unique_ptr<HyperelasticLaw>> shear_laws;  ///< per tissue, nodal pressure only
  std::vector<const HyperelasticLaw*> law;             ///< per element: what the element integrates
  std::vector<const HyperelasticLaw*> full_law;        ///< per element: the tissue's law
  std::vector<int> tissue;                             ///< per element, 0-based
  std::vector<ElementGeometry> geometry;               ///< per element, model length unit
  Eigen::VectorXd f_ext;                               ///< global (3 per node), lambda = 1
  std::unique_ptr<NodalPressure> nodal;                ///< tet4 with tet4_pressure: nodal
};

void check_model(const Model& model, const SolveOptions& options) {
  validate_model(model);
  for (std::size_t t = 0; t < model.materials.size(); ++t)
    if (!(model.materials[t].density_kg_m3 > 0.0))
      throw InputError("tissue '" + model.tissue_names.at(t) + "' has density " +
                       std::to_string(model.materials[t].density_kg_m3) +
                       " kg/m^3: every tissue needs a positive density for a gravity solve");
  bool held = !options.prescribed.empty();
  for (const NodeSet& set : model.node_sets) held = held || !set.nodes.empty();
  if (!held)
    throw InputError("model '" + model.title +
                     "' has no fixed or sliding node set: it is not held in place and cannot be solved statically");
  if (!std::isfinite(options.gravity_scale)) throw InputError("gravity scale must be finite");
  if (!options.initial_displacements.empty()) {
    if (options.initial_displacements.size() != model.nodes.size())
      throw InputError("initial displacements: " + std::to_string(options.initial_displacements.size()) +
                       " vectors for a model of " + std::to_string(model.nodes.size()) + " nodes");
    for (std::size_t v = 0; v < model.nodes.size(); ++v)
      if (!options.initial_displacements[v].allFinite())
        throw InputError("initial displacement of node " + std::to_string(v) + " is not finite");
  }
  const AnalysisSettings& s = model.analysis;
  if (s.load_steps < 1 || s.max_newton_iterations < 1 || !(s.min_step_fraction > 0.0) || s.max_load_steps < 1)
    throw InputError(
        "analysis settings: load_steps, max_newton_iterations, max_load_steps and min_step_fraction must be positive");
}

Problem build_problem(const Model& model, const SolveOptions& options) {
  Problem p;
  const UnitSystem units = model.units;
  for (const MaterialSpec& spec : model.materials) p.laws.push_back(make_law(spec, units));
  const bool nodal = uses_nodal_pressure(model);
  if (nodal)
    for (const auto& law : p.laws) p.shear_laws.push_back(make_shear_part(*law));

  Eigen::Vector3d g;
  for (int i = 0; i < 3; ++i)
    g[i] = acceleration_from_m_per_s2(units, model.gravity.acceleration_m_s2[i]) * options.gravity_scale;

  const int n = model.nodes_per_element();
  p.f_ext = Eigen::VectorXd::Zero(3 * static_cast<Eigen::Index>(model.nodes.size()));
  p.geometry.resize(model.elements.size());
  p.law.resize(model.elements.size());
  p.full_law.resize(model.elements.size());
  p.tissue.resize(model.elements.size());
  ElementNodes X(n, 3);
  for (std::size_t e = 0; e < model.elements.size(); ++e) {
    for (int a = 0; a < n; ++a)
      for (int i = 0; i < 3; ++i) X(a, i) = length_from_mm(units, model.nodes[model.elements[e][a]][i]);
    if (element_geometry(model.order, X, p.geometry[e]) != ElementStatus::Ok)
      throw SolverError("element " + std::to_string(e) + " is inverted or flat in the reference configuration");
    const int tissue = model.tissue_ids[e] - 1;
    p.tissue[e] = tissue;
    p.full_law[e] = p.laws.at(tissue).get();
    p.law[e] = nodal ? p.shear_laws.at(tissue).get() : p.full_law[e];
    const double rho = density_from_kg_per_m3(units, model.materials[tissue].density_kg_m3);
    const ElementVector fb = element_body_force(model.order, X, rho, g);
    for (int a = 0; a < n; ++a) p.f_ext.segment<3>(3 * model.elements[e][a]) += fb.segment<3>(3 * a);
  }
  if (nodal) p.nodal = std::make_unique<NodalPressure>(model.elements, p.geometry, p.tissue, p.full_law);
  return p;
}

/// The state Newton works on: reduced unknowns, the global displacement and forces there.
struct State {
  Eigen::VectorXd q;      ///< reduced unknowns
  Eigen::VectorXd u;      ///< global displacement
  Eigen::VectorXd f_int;  ///< global internal force at u
};

/// Solver-wide pieces shared by the increments.
struct Context {
  const Problem& problem;
  const DofMap& dofs;
  const AnalysisSettings& settings;
  ReducedAssembly& assembly;
  SparseSpdSolver& linear;
  double assembly_seconds = 0.0;
  double linear_seconds = 0.0;
  int tangent_assemblies = 0;
  int force_assemblies = 0;

  ReducedAssembly::Result assemble(const Eigen::VectorXd& u, bool tangent) {
    const auto t = Clock::now();
    ReducedAssembly::Result r = assembly.assemble(u, tangent);
    assembly_seconds += seconds_since(t);
    ++(tangent ? tangent_assemblies : force_assemblies);
    return r;
  }
};

/// Residual reference: the larger of the load and the internal force over all dofs. With gravity
/// alone this is about the weight's scale; with prescribed motion and no load, the reactions'.
double residual_scale(const Eigen::VectorXd& load, const Eigen::VectorXd& f_int) {
  const double s = std::max(load.norm(), f_int.norm());
  return s > 0.0 ? s : 1.0;
}

/// One load increment: Newton to lambda from the predicted reduced unknowns `guess`, or from
/// `fallback` (the last accepted state) when the prediction inverts an element or its first
/// linear solve fails. On success `out` holds the new state.
bool newton_increment(Context& ctx, double lambda, const Eigen::VectorXd& guess, const Eigen::VectorXd& fallback,
                      State& out, StepRecord& record) {
  const DofMap& dofs = ctx.dofs;
  const AnalysisSettings& s = ctx.settings;
  const Eigen::VectorXd load = lambda * ctx.problem.f_ext;
  const Eigen::VectorXd load_reduced = dofs.reduce(load);

  State trial;
  ReducedAssembly::Result current;
  Eigen::VectorXd R;
  double rnorm = 0.0, potential = 0.0, ref = 1.0;
  // Newton's start: trial, its forces and residual at q; false when an element inverts there.
  // The convergence test of an increment (static_solver.h): residual norm against its reference,
  // the last correction's norm against that of the unknowns.
  auto meets_tolerances = [&](double r_norm, double r_ref, double step_norm, double q_norm) {
    return r_norm <= s.residual_tolerance * r_ref && step_norm <= s.displacement_tolerance * q_norm;
  };
  auto start_at = [&](const Eigen::VectorXd& q) {
    trial.q = q;
    trial.u = dofs.expand(trial.q, lambda);
    current = ctx.assemble(trial.u, true);
    if (!current.ok) return false;
    R = load_reduced - dofs.reduce(current.f_int);
    rnorm = R.norm();
    potential = current.energy - load.dot(trial.u);  // total potential energy at trial.u
    ref = residual_scale(load, current.f_int);
    return true;
  };
  if (!start_at(guess) && (guess == fallback || !start_at(fallback))) {
    record.note = current.note;
    return false;
  }
  record.residual_norms.push_back(rnorm / ref);
  if (!std::isfinite(rnorm)) {
    record.note = "non-finite residual";
    return false;
  }
  if (rnorm == 0.0) {  // nothing to do (no load, nothing prescribed)
    trial.f_int = std::move(current.f_int);
    out = std::move(trial);
    return true;
  }
  for (int it = 1; it <= s.max_newton_iterations; ++it) {
    record.iterations = it;
    Eigen::VectorXd dq;
    const auto t = Clock::now();
    const double forcing = std::clamp(rnorm / ref, kMinForcing, kMaxForcing);
    const bool solved = ctx.linear.solve(ctx.assembly.tangent(), R, dq, forcing);
    ctx.linear_seconds += seconds_since(t);
    if (!solved && it == 1 && trial.q != fallback) {
      // The predicted state's tangent is too far from positive definite for the shift ladder
      // (seen with the nodal-pressure tet4 after a doubled increment): start again from the last
      // accepted state, whose tangent is that of a stable equilibrium, before cutting back.
      if (!start_at(fallback)) {
        record.note = current.note;
        return false;
      }
      record.residual_norms.back() = rnorm / ref;
      --it;
      continue;
    }
    if (!solved) {
      record.note = "linear solve failed (singular or non-finite tangent)";
      return false;
    }
    // Backtracking line search: the longest step (1, 1/2, ... 1/16) that lowers either the
    // potential energy Pi = W(u) - load . u or ||R||. Far from equilibrium a full Newton step often
    // lowers the energy while ||R|| grows (stiffening in compression), and refusing it costs
    // iterations; near equilibrium ||R|| decides (the energy change is then at round-off level).
    // The full step is evaluated with the tangent (it is almost always taken), unless it is
    // expected to end the increment (below); shorter ones with the force only. The kept step gets
    // its tangent afterwards when it has none and the increment goes on. When no step lowers
    // either, the one with the smallest ||R|| is kept.
    // Expected to end the increment: the full step meets the displacement test, and the inexact
    // Newton model's next residual, forcing x ||R|| (quadratic convergence with the linear solve's
    // relative accuracy), meets the residual test. Its tangent would go unused (the next increment
    // starts from its own predicted state). When it does not end the increment after all, its
    // tangent is assembled at once and the step goes on as if it had been evaluated with it (a
    // failing tangent rules it out, as before). So the Newton path is the same, except that a step
    // that ends its increment is accepted on its force alone: a non-finite tangent there would
    // only show at the next increment's start. About one tangent in four is saved this way, and a
    // prediction that misses costs one force evaluation.
    const double rel = rnorm / ref;
    const bool expect_end = rel * std::clamp(rel, kMinForcing, kMaxForcing) <= s.residual_tolerance &&
                            dq.norm() <= s.displacement_tolerance * (trial.q + dq).norm();
    double best_norm = INFINITY, best_alpha = 0.0, best_potential = 0.0;
    bool best_has_tangent = false;
    ReducedAssembly::Result best;
    Eigen::VectorXd best_R, best_q;
    std::string inverted_note;
    for (double alpha = 1.0; alpha >= 1.0 / 16.0; alpha *= 0.5) {
      Eigen::VectorXd q = trial.q + alpha * dq;
      const Eigen::VectorXd ua = dofs.expand(q, lambda);
      bool with_tangent = alpha == 1.0 && !expect_end;
      ReducedAssembly::Result a = ctx.assemble(ua, with_tangent);
      if (!a.ok) {
        inverted_note = a.note;
        continue;
      }
      Eigen::VectorXd Ra = load_reduced - dofs.reduce(a.f_int);
      const double na = Ra.norm();
      const double pa = a.energy - load.dot(ua);
      if (!std::isfinite(na) || !std::isfinite(pa)) continue;
      if (alpha == 1.0 && expect_end && !meets_tolerances(na, residual_scale(load, a.f_int), dq.norm(), q.norm())) {
        ReducedAssembly::Result full = ctx.assemble(ua, true);  // the prediction missed
        if (!full.ok) {
          inverted_note = full.note;
          continue;
        }
        a = std::move(full);  // the same force and energy, bit for bit
        with_tangent = true;
      }
      const bool descends = na < rnorm || pa < potential;
      if (na < best_norm || descends) {
        best_norm = na;
        best_alpha = alpha;
        best_has_tangent = with_tangent;
        best_potential = pa;
        best = std::move(a);
        best_R = std::move(Ra);
        best_q = std::move(q);
      }
      if (descends) break;
    }
    if (best_alpha == 0.0) {
      record.note = inverted_note.empty() ? "non-finite residual" : inverted_note;
      return false;
    }
    trial.q = std::move(best_q);
    trial.u = dofs.expand(trial.q, lambda);
    R = std::move(best_R);
    rnorm = best_norm;
    potential = best_potential;
    ref = residual_scale(load, best.f_int);
    record.step_lengths.push_back(best_alpha);
    record.residual_norms.push_back(rnorm / ref);
    if (meets_tolerances(rnorm, ref, best_alpha * dq.norm(), trial.q.norm())) {
      trial.f_int = std::move(best.f_int);
      out = std::move(trial);
      return true;
    }
    if (rnorm > 1e12 * ref) {
      record.note = "diverged (residual grew beyond 1e12 of the load)";
      return false;
    }
    if (!best_has_tangent) {  // the tangent at the kept point was not assembled yet
      best = ctx.assemble(trial.u, true);
      if (!best.ok) {
        record.note = best.note;
        return false;
      }
    }
  }
  record.note = "no convergence in " + std::to_string(s.max_newton_iterations) + " Newton iterations";
  return false;
}

}  // namespace

// The linear solver and what identifies the unknowns it was analysed for.
struct SolverWorkspace::Impl {
  std::unique_ptr<SparseSpdSolver> linear;
  LinearSolverKind kind = LinearSolverKind::Auto;
  std::vector<int> groups;
  std::size_t elements = 0;
  int solves = 0;

  SparseSpdSolver& get(LinearSolverKind k, int threads, std::vector<int> g, std::size_t num_elements) {
    if (!linear) {
      kind = k;
      groups = g;
      elements = num_elements;
      linear = std::make_unique<SparseSpdSolver>(k, threads, std::move(g));
    } else if (k != kind || g != groups || num_elements != elements) {
      throw std::invalid_argument(
          "SolverWorkspace: a solve with other unknowns or elements than the first one it served");
    }
    ++solves;
    return *linear;
  }
};

SolverWorkspace::SolverWorkspace() : impl(std::make_unique<Impl>()) {}
SolverWorkspace::~SolverWorkspace() = default;
int SolverWorkspace::solves() const { return impl->solves; }
void SolverWorkspace::forget_factorisation() {
  if (impl->linear) impl->linear->forget_factorisation();
}

std::string formulation_name(const Model& model) {
  if (model.order == ElementOrder::Quadratic) return "tet10";
  return uses_nodal_pressure(model) ? "tet4, average nodal pressure" : "tet4";
}

SolveResult solve_static(const Model& model, const SolveOptions& options) {
  const auto start = Clock::now();
  check_model(model, options);
  const DofMap dofs(model, options.prescribed);
  const Problem problem = build_problem(model, options);
  const AnalysisSettings& s = model.analysis;
  ReducedAssembly assembly(model.order, model.elements, problem.geometry, problem.law, dofs, options.threads,
                           problem.nodal.get());
  std::unique_ptr<SparseSpdSolver> own_linear;
  SparseSpdSolver& linear =
      options.workspace
          ? options.workspace->impl->get(options.linear_solver, assembly.threads(), dofs.node_groups(),
                                         model.elements.size())
          : *(own_linear = std::make_unique<SparseSpdSolver>(options.linear_solver, assembly.threads(),
                                                              dofs.node_groups()));
  // A shared linear solver counts over all its solves: this solve reports its own share.
  const int factorisations_before = linear.factorisations(), shifted_before = linear.shifted_factorisations(),
            failed_before = linear.failed_factorisations(), iterations_before = linear.iterations(),
            eigen_before = linear.eigenvalue_iterations();
  const double factorisation_seconds_before = linear.factorisation_seconds(),
               analysis_seconds_before = linear.analysis_seconds();
  Context ctx{problem, dofs, s, assembly, linear};

  SolveResult result;
  result.free_dofs = dofs.num_free();
  result.linear_solver = linear.name();
  result.formulation = formulation_name(model);
  result.threads = assembly.threads();

  State state;
  state.q = Eigen::VectorXd::Zero(dofs.num_free());
  state.u = Eigen::VectorXd::Zero(problem.f_ext.size());
  state.f_int = Eigen::VectorXd::Zero(problem.f_ext.size());
  Eigen::VectorXd previous_q = state.q;  // accepted state before the last one (for the predictor)
  double previous_increment = 0.0;
  bool after_cut_back = false;  // the last attempt failed and was halved
  double lambda = 0.0, increment = 1.0 / s.load_steps;
  bool failed = false;
  if (!options.initial_displacements.empty()) {
    // The whole load at once from the given start; a failure falls back to the ramp from zero.
    Eigen::VectorXd u0(problem.f_ext.size());
    for (std::size_t v = 0; v < model.nodes.size(); ++v) u0.segment<3>(3 * v) = options.initial_displacements[v];
    const Eigen::VectorXd q0 = dofs.reduce(u0);  // B^T u: the components the constraints allow
    const auto step_start = Clock::now();
    StepRecord record;
    record.load_fraction = 1.0;
    record.increment = 1.0;
    State next;
    const bool ok = newton_increment(ctx, 1.0, q0, q0, next, record);
    result.total_iterations += record.iterations;
    record.accepted = ok;
    record.note = ok ? "from the initial displacement" : "from the initial displacement: " + record.note;
    record.seconds = seconds_since(step_start);
    if (options.on_step) options.on_step(record);
    if (ok) {
      state = std::move(next);
      lambda = 1.0;
    }
    result.steps.push_back(std::move(record));
  }
  while (lambda < 1.0) {
    if (static_cast<int>(result.steps.size()) >= s.max_load_steps) {
      result.message = "stopped after " + std::to_string(s.max_load_steps) +
                       " load increments (max_load_steps) at load fraction " + std::to_string(lambda);
      failed = true;
      break;
    }
    const auto step_start = Clock::now();
    StepRecord record;
    const double target = (1.0 - lambda <= increment * (1.0 + 1e-9)) ? 1.0 : lambda + increment;
    record.load_fraction = target;
    record.increment = target - lambda;
    // Secant predictor: extrapolate the last accepted increment (the load path is smooth); it
    // typically saves one Newton iteration per increment. Newton starts from the last accepted
    // state instead when the extrapolated one inverts an element, and never right after a cut-back.
    Eigen::VectorXd guess = state.q;
    if (previous_increment > 0.0)
      guess += (record.increment / previous_increment) * (state.q - previous_q);
    State next;
    const bool ok = newton_increment(ctx, target, guess, state.q, next, record);
    result.total_iterations += record.iterations;
    record.accepted = ok;
    record.seconds = seconds_since(step_start);
    if (options.on_step) options.on_step(record);
    if (ok) {
      previous_q = state.q;
      previous_increment = record.increment;
      state = std::move(next);
      lambda = target;
      if (record.iterations <= kQuickIterations && !after_cut_back)
        increment = std::min(1.0, 4.0 * increment);
      else if (record.iterations <= kEasyIterations)
        increment = std::min(1.0, 2.0 * increment);
      after_cut_back = false;
      result.steps.push_back(std::move(record));
      continue;
    }
    previous_increment = 0.0;  // no extrapolation across a cut-back
    after_cut_back = true;
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
  for (std::size_t v = 0; v < model.nodes.size(); ++v) {
    result.displacements[v] = state.u.segment<3>(3 * v);  // already in the model's length unit
    result.total_load += problem.f_ext.segment<3>(3 * v);
  }
  for (int v : dofs.constrained_nodes()) {
    NodeReaction r;
    r.node = v;
    r.force = dofs.constrained_part(v, state.f_int.segment<3>(3 * v) - lambda * problem.f_ext.segment<3>(3 * v));
    result.total_reaction += r.force;
    result.reactions.push_back(r);
  }
  result.assembly_seconds = ctx.assembly_seconds;
  result.tangent_assemblies = ctx.tangent_assemblies;
  result.force_assemblies = ctx.force_assemblies;
  result.linear_solve_seconds = ctx.linear_seconds;
  result.factorisations = linear.factorisations() - factorisations_before;
  result.shifted_factorisations = linear.shifted_factorisations() - shifted_before;
  result.failed_factorisations = linear.failed_factorisations() - failed_before;
  result.linear_iterations = linear.iterations() - iterations_before;
  result.eigenvalue_iterations = linear.eigenvalue_iterations() - eigen_before;
  result.numeric_factorisation = linear.numeric_factorisation();
  result.cg_preconditioner = linear.preconditioner();
  result.factorisation_seconds = linear.factorisation_seconds() - factorisation_seconds_before;
  result.analysis_seconds = linear.analysis_seconds() - analysis_seconds_before;
  result.factor_entries = linear.factor_entries();
  result.factor_flops = linear.factor_flops();
  if (result.converged) {
    std::ostringstream msg;
    msg << "converged: " << result.steps.size() << " increments, " << result.total_iterations
        << " Newton iterations";
    result.message = msg.str();
  }
  result.seconds = seconds_since(start);
  return result;
}

}  // namespace tissuemesh
