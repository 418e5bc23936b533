// Built-in nonlinear static solver (issue #4): total-Lagrangian finite elements on the model's
// tet4/tet10 mesh, the model's own hyperelastic laws, dead gravity load.
//
// Units: everything is solved in the model's unit system (model.units). Nodes (stored in mm) are
// converted with length_from_mm, densities with density_from_kg_per_m3, gravity with
// acceleration_from_m_per_s2, laws come from make_law(spec, model.units). Results are in the same
// system: displacements in length_unit(model.units) (mm for mm-t-s), forces in its force unit
// (N for mm-t-s and SI, mN for mm-kg-s).
//
// Problem: find u with  R(u) = lambda f_ext - f_int(u) = 0  on the free dofs, lambda = 1 at the
// end. f_ext is the consistent body force int N rho g dV over the reference volume (dead load);
// f_int and the tangent K = d f_int / du come from element_response (solver_check/element_kernel.h).
// Assembly is serial, in element order, so the result is bit-for-bit deterministic.
//
// Constraints: every dof of a node in a Fixed node set is eliminated (u = 0). Sliding node sets
// are NOT supported yet: solve_static throws SolverError ("not supported yet") for a model that
// has one.
//
// Algorithm (settings from model.analysis, see core/model.h AnalysisSettings):
// - load stepping: starts with load_steps equal increments; an increment that fails (Newton
//   diverges or produces a non-finite value, an element inverts (J <= 0), the linear solve fails,
//   or more than max_newton_iterations are needed) is retried with half the increment; the
//   increment never drops below min_step_fraction (then the solve stops, converged = false).
//   After two successive accepted increments the increment doubles again, up to the initial one.
//   At most max_load_steps increments are attempted, cut-backs included.
// - Newton-Raphson with the consistent tangent, solved by Eigen::SimplicialLDLT on the free dofs
//   (lower triangle; the sparsity pattern is analysed once and reused for every factorisation);
//   backtracking line search on the residual norm: step lengths 1, 1/2, ... 1/16, the first that
//   lowers ||R|| (and keeps every element un-inverted) is taken; when none lowers it the
//   un-inverted trial with the smallest ||R|| is taken.
// - convergence of an increment: ||R_free|| <= residual_tolerance * ||lambda f_ext,free|| AND
//   ||delta u_free|| <= displacement_tolerance * ||u_free|| for the last correction
//   (energy_tolerance is FEBio's and not used here).
//
// Refused up front (nothing solved): anything validate_model refuses (InputError); no Fixed node
// set, or Fixed sets without nodes (InputError: the model would float); a tissue with zero or
// negative density (InputError naming it); an inverted reference element (SolverError).
// A solve that cannot finish does not throw: converged = false, message says why, and the
// displacements/reactions are those of the last accepted increment (never NaN).
#pragma once

#include "core/model.h"

#include <Eigen/Core>

#include <string>
#include <vector>

namespace tissuemesh {

struct SolveOptions {
  /// Multiplies the model's gravity (1 = as in the model). Used e.g. for small-load linear checks.
  double gravity_scale = 1.0;
};

/// One attempted load increment.
struct StepRecord {
  double load_fraction = 0.0;  ///< lambda at the end of the increment (the target of the attempt)
  double increment = 0.0;      ///< delta lambda of the attempt
  int iterations = 0;          ///< Newton iterations performed
  /// ||R_free|| / ||lambda f_ext,free|| after each iteration (first entry: before any iteration).
  std::vector<double> residual_norms;
  bool accepted = false;       ///< false: cut back (see note)
  std::string note;            ///< why it was cut ("inverted element 12", "diverged", ...)
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
  /// Reactions at the nodes of the Fixed sets, sorted by node: f_int - lambda f_ext there, so that
  /// sum of reactions + lambda * total_load = 0 at equilibrium. Model force unit.
  std::vector<NodeReaction> reactions;
  Eigen::Vector3d total_reaction = Eigen::Vector3d::Zero();
  Eigen::Vector3d total_load = Eigen::Vector3d::Zero();  ///< sum of f_ext at lambda = 1 (weight)
  std::vector<StepRecord> steps;  ///< every attempted increment, in order
  int total_iterations = 0;
  double seconds = 0.0;           ///< wall time of the solve
};

/// Solves model under its gravity (scaled by options.gravity_scale). See the header comment.
SolveResult solve_static(const Model& model, const SolveOptions& options = {});

}  // namespace tissuemesh
