// Built-in nonlinear static solver: total-Lagrangian finite elements on the model's tet4/tet10
// mesh, the model's own hyperelastic laws, dead gravity load (docs/solver.md).
//
// Units: everything is solved in the model's unit system (model.units). Nodes (stored in mm) are
// converted with length_from_mm, densities with density_from_kg_per_m3, gravity with
// acceleration_from_m_per_s2, laws come from make_law(spec, model.units). Results are in the same
// system: displacements in length_unit(model.units) (mm for mm-t-s), forces in its force unit
// (N for mm-t-s and SI, mN for mm-kg-s).
//
// Problem: find u with  R(u) = lambda f_ext - f_int(u) = 0  on the free dofs, lambda = 1 at the
// end. f_ext is the consistent body force int N rho g dV over the reference volume (dead load);
// f_int and the tangent K = d f_int / du come from the element kernel (solver_check/element_kernel.h).
//
// Constraints (solver_check/dof_map.h): a node of a Fixed set has u = 0; a node of a Sliding set
// moves only tangentially, n . u = 0 for each of its sets' normals (two sliding sets at a node
// leave the line along n1 x n2, three or a fixed set leave nothing); a node in
// SolveOptions::prescribed follows lambda * value in all three components (overrides the sets).
// The solver works in each node's reduced basis (the unconstrained directions), so constraints
// are exact and the tangent stays symmetric positive definite where the material is stable.
//
// Algorithm (settings from model.analysis, AnalysisSettings in core/model.h; docs/solver.md,
// "Newton iterations and load stepping"):
// - load stepping: the first increment is 1/load_steps; an increment that fails (Newton diverges
//   or produces a non-finite value, an element inverts (J <= 0), the linear solve fails, or more
//   than max_newton_iterations are needed) is retried at half the size, never below
//   min_step_fraction (then the solve stops, converged = false). An increment that converged in
//   at most 4 Newton iterations doubles the next one, in at most 3 quadruples it (only doubles
//   right after a cut-back), never beyond the rest of the load: load_steps sets the first
//   increment, not the number of increments. At most max_load_steps increments are attempted,
//   cut-backs included.
// - Newton-Raphson with the consistent tangent, inexact linear solves
//   (solver_check/linear_solver.h) and a backtracking line search on the potential energy
//   W(u) - load . u and ||R|| (step lengths 1 .. 1/16); each increment starts from a secant
//   prediction.
// - convergence of an increment: ||R_free|| <= residual_tolerance * max(||lambda f_ext||,
//   ||f_int||) (norms over all dofs: the load's scale under gravity, the reactions' scale for a
//   prescribed motion without load) AND ||delta q|| <= displacement_tolerance * ||q|| for the last
//   correction, q the reduced unknowns (energy_tolerance is FEBio's and not used here).
// - assembly runs in parallel over elements (OpenMP) into a precomputed sparsity pattern and is
//   scattered in element order, so every matrix entry is summed in the same order whatever the
//   thread count: results are bit-for-bit deterministic (solver_check/reduced_assembly.h).
// - tet4 with model.analysis.tet4_pressure = nodal integrates each law's volumetric part U(J) per
//   node and tissue instead of per element (average nodal pressure, solver_check/nodal_pressure.h):
//   no volumetric locking at nu -> 0.5, a wider tangent. tet10 ignores the setting.
//
// Refused up front (nothing solved): anything validate_model refuses (InputError); a model with no
// constraint at all (no Fixed set with nodes and nothing prescribed: InputError, it would float);
// a tissue with zero or negative density (InputError naming it); an inverted reference element
// (SolverError); a prescribed node index out of range or a non-finite prescribed value
// (InputError). Sliding sets alone are accepted when they hold the model (a singular tangent then
// fails the linear solve and is reported).
// A solve that cannot finish does not throw: converged = false, message says why, and the
// displacements/reactions are those of the last accepted increment (never NaN).
#pragma once

#include "core/model.h"

#include <Eigen/Core>

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace tissuemesh {

/// A node whose displacement is imposed: u = lambda * value (model length unit) in all components.
struct PrescribedDisplacement {
  int node = 0;  ///< 0-based model node index
  Eigen::Vector3d value = Eigen::Vector3d::Zero();
};

enum class LinearSolverKind {
  Auto,            ///< CHOLMOD supernodal when built with it, else SimplicialLDLT
  Cholmod,         ///< CHOLMOD supernodal LLT (SolverError when the build lacks it)
  SimplicialLDLT,  ///< Eigen's own sparse LDL^T
};

/// One attempted load increment.
struct StepRecord {
  double load_fraction = 0.0;  ///< lambda at the end of the increment (the target of the attempt)
  double increment = 0.0;      ///< delta lambda of the attempt
  int iterations = 0;          ///< Newton iterations performed
  /// ||R_free|| / max(||lambda f_ext||, ||f_int||) after each iteration (first entry: before any).
  std::vector<double> residual_norms;
  /// Line-search step length taken in each iteration (1 = full Newton step).
  std::vector<double> step_lengths;
  bool accepted = false;       ///< false: cut back (see note)
  std::string note;            ///< why it was cut ("inverted element 12", "diverged", ...)
  double seconds = 0.0;        ///< wall time of the attempt
};

/// What consecutive solves of one mesh share (reference-state iterations, parameter sweeps): the
/// linear solver's fill-reducing ordering and symbolic analysis, computed by the first solve, and
/// its last factorisation, which preconditions the next solve's first tangents. Give the same
/// workspace only to solves whose models have the same elements, element order, constraints and
/// tet4_pressure (node positions, materials and loads may differ); solve_static throws
/// std::invalid_argument when the unknowns differ from the first solve's. One solve at a time.
class SolverWorkspace {
 public:
  SolverWorkspace();
  ~SolverWorkspace();
  SolverWorkspace(const SolverWorkspace&) = delete;
  SolverWorkspace& operator=(const SolverWorkspace&) = delete;
  /// Solves that used it so far.
  int solves() const;
  /// Drops the kept factorisation (the analysis stays): the next solve's result then depends only
  /// on its model and start, not on the solves before it (sweeps that must be reproducible).
  void forget_factorisation();
  struct Impl;  ///< defined in static_solver.cpp
  std::unique_ptr<Impl> impl;
};

struct SolveOptions {
  /// Multiplies the model's gravity (1 = as in the model). Used e.g. for small-load linear checks.
  double gravity_scale = 1.0;
  /// Imposed displacements (ramped with the load). Empty for the usual gravity solve.
  std::vector<PrescribedDisplacement> prescribed;
  LinearSolverKind linear_solver = LinearSolverKind::Auto;
  /// Threads for assembly (CHOLMOD's BLAS: 1, see linear_solver.h); 0 = $OMP_NUM_THREADS, else all
  /// processors.
  int threads = 0;
  /// Where Newton starts: one displacement per model node (model length unit), e.g. a nearby
  /// problem's solution. The solve first tries the whole load in one increment from it (its
  /// constrained components dropped); when that increment fails, the usual ramp from zero follows.
  /// Empty (default): the ramp. A wrong length or a non-finite value: InputError.
  std::vector<Eigen::Vector3d> initial_displacements;
  /// Shared by consecutive solves of one mesh (SolverWorkspace); null: the solve's own.
  SolverWorkspace* workspace = nullptr;
  /// Called after every attempted increment, e.g. to print progress; may be empty.
  std::function<void(const StepRecord&)> on_step;
};

struct NodeReaction {
  int node = 0;                ///< 0-based model node index
  Eigen::Vector3d force = Eigen::Vector3d::Zero();  ///< force of the support on the body
};

struct SolveResult {
  bool converged = false;      ///< true when lambda = 1 was reached
  std::string message;         ///< summary, or the reason for failure
  double load_fraction = 0.0;  ///< last accepted lambda
  /// Per model node, length unit of model.units (the last accepted state if not converged).
  std::vector<Eigen::Vector3d> displacements;
  /// Reactions at every constrained node (fixed, sliding or prescribed), sorted by node: the
  /// constrained components of f_int - lambda f_ext there (a sliding node's reaction is along its
  /// normal(s)), so that sum of reactions + lambda * total_load = 0 at equilibrium. Force unit.
  std::vector<NodeReaction> reactions;
  Eigen::Vector3d total_reaction = Eigen::Vector3d::Zero();
  Eigen::Vector3d total_load = Eigen::Vector3d::Zero();  ///< sum of f_ext at lambda = 1 (weight)
  std::vector<StepRecord> steps;  ///< every attempted increment, in order
  int total_iterations = 0;
  int free_dofs = 0;              ///< unknowns after constraints
  std::string linear_solver;      ///< "CHOLMOD supernodal LLT" or "Eigen SimplicialLDLT"
  std::string numeric_factorisation;  ///< SparseSpdSolver::numeric_factorisation()
  std::string formulation;       ///< formulation_name(model)
  int threads = 1;                ///< assembly threads used
  int factorisations = 0;         ///< numeric factorisations of the tangent (this solve's)
  int shifted_factorisations = 0; ///< of them, with a diagonal shift (tangent not positive definite)
  int failed_factorisations = 0;  ///< attempts given up (not positive definite), not in the above
  int linear_iterations = 0;      ///< preconditioned CG iterations on kept factorisations
  int eigenvalue_iterations = 0;  ///< LOBPCG iterations estimating indefinite tangents' lowest eigenvalue
  std::string cg_preconditioner;  ///< SparseSpdSolver::preconditioner()
  double assembly_seconds = 0.0;  ///< wall time in element evaluation and assembly
  /// Assemblies of force and tangent (each Newton direction needs one at its start point, so at
  /// least total_iterations) and of the force alone (line-search trials, and full steps expected
  /// to end their increment, whose tangent would go unused).
  int tangent_assemblies = 0;
  int force_assemblies = 0;
  double linear_solve_seconds = 0.0;  ///< wall time in factorisation and solves
  double factorisation_seconds = 0.0; ///< of it, in numeric factorisations
  double analysis_seconds = 0.0;  ///< of it, in the one symbolic analysis (ordering) and its planning
                                  ///< (0 when a SolverWorkspace already held it)
  double factor_entries = 0.0;    ///< entries of the tangent's factor (SparseSpdSolver::factor_entries)
  double factor_flops = 0.0;      ///< flops of one factorisation (SparseSpdSolver::factor_flops; 0 = unknown)
  double seconds = 0.0;           ///< wall time of the solve
};

/// Solves model under its gravity (scaled by options.gravity_scale). See the header comment.
SolveResult solve_static(const Model& model, const SolveOptions& options = {});

/// The element formulation solve_static uses for this model: "tet4", "tet4, average nodal
/// pressure" (tet4 with analysis.tet4_pressure: nodal) or "tet10".
std::string formulation_name(const Model& model);

/// True when this build links CHOLMOD (SuiteSparse).
bool cholmod_available();

}  // namespace tissuemesh
