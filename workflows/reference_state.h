// Estimating the unloaded (stress-free) reference configuration of a body imaged under gravity, by
// the fixed-point "backward displacement" iteration (Sellier, J. Fluids Struct. 27:1461, 2011;
// Bols et al., J. Comput. Appl. Math. 246:10, 2013), with the relaxation rule of UCL's
// referenceStateEstimation (docs/prone-to-supine.md, "Reference state"):
//
//   X_0     = x + u(x; -g)                    naive reversal: the imaged shape loaded by -g
//   X_{k+1} = X_k - alpha_k (phi(X_k; g) - x)  phi(X; g): X deformed by the forward solve under g
//
// x: the imaged (loaded) node positions, g: the model's gravity. The mismatch of X_k is
// max over mesh nodes |phi(X_k) - x|. alpha starts at `initial`; after an improvement on the best
// mismatch so far alpha <- min(growth alpha, 1); after a worsening, a failed forward solve or an
// update that would invert an element, alpha <- cut alpha and the update restarts from the best
// iterate. It stops when the mismatch is at most tolerance_mm (converged), after max_iterations
// forward solves, or when alpha falls below 1e-3 (stagnation).
// Acceleration: the updates from accepted iterates are Anderson-mixed (workflows/anderson_mixing.h,
// memory anderson_memory; the history restarts at every rejection). Plain relaxation contracts
// the error by |1 - alpha mu| per iteration for each eigenvalue mu of d phi / dX; a soft body hanging
// under gravity has a smooth mode with mu near 0 (its loaded shape hardly depends on its reference),
// where plain relaxation stalls (0.4 % per iteration on the default phantom) and Anderson's secant
// step converges.
//
// Nodes: X moves at the mesh (corner) nodes; tet10 midside nodes stay at their edges' midpoints
// (straight-edged reference elements, like every mesh the toolkit writes), and the mismatch is
// measured at corner nodes. Constraints are the model's (a fixed node keeps u = 0, so its X is x;
// a sliding node moves in its plane).
// Cost: every forward solve starts where its deformed shape is x (X_0 from -u_rev, later ones from
// the previous displacement corrected by the update, u_k + X_k - X_{k+1}) and all solves share one
// SolverWorkspace (ordering, symbolic analysis, last factor), so each takes a few Newton
// iterations where a solve from zero takes a load ramp.
//
// Units: positions and distances in mm (Model nodes are mm), whatever model.units.
// Throws what solve_static refuses up front (InputError, SolverError for an inverted input
// element), and InputError when the model has no gravity. Does not throw when the iteration fails
// to converge: converged = false, message says why, and the result holds the best iterate (never a
// non-finite value).
#pragma once

#include "core/model.h"
#include "solver_check/static_solver.h"

#include <Eigen/Core>

#include <functional>
#include <string>
#include <vector>

namespace tissuemesh {

struct ReferenceStateOptions {
  double tolerance_mm = 0.01;
  int max_iterations = 30;   ///< forward solves under g, the one of X_0 included
  double relaxation_initial = 0.7;
  double relaxation_growth = 1.05;
  double relaxation_cut = 0.7;
  int anderson_memory = 5;   ///< Anderson acceleration's memory (0: plain relaxation, UCL's rule)
  int threads = 0;           ///< assembly threads (solve_static)
};

/// One forward solve of the iteration (index 0: the naive reversal X_0 loaded by g).
struct ReferenceIteration {
  int index = 0;
  double alpha = 0.0;           ///< the relaxation that produced this iterate (0 for X_0)
  bool solved = false;          ///< the forward solve converged (else mismatch is not measured)
  double mismatch_mm = 0.0;     ///< max nodal |phi(X) - x| over mesh nodes (when solved)
  bool improved = false;        ///< a new best iterate
  int newton_iterations = 0;
  int increments = 0;           ///< load increments attempted
  double seconds = 0.0;         ///< wall time of the forward solve
  std::string note;             ///< why it was rejected, or the solver's message
};

struct ReferenceStateResult {
  bool converged = false;
  std::string message;
  /// The best iterate: every model node (midside nodes at their edges' midpoints), mm.
  std::vector<Eigen::Vector3d> reference_nodes;
  /// Its forward solve under g: displacement per model node, mm; phi(X) = X + u (the prone check).
  std::vector<Eigen::Vector3d> loaded_displacements_mm;
  bool measured = false;           ///< some iterate was solved (else the mismatches are 0 and unused)
  double mismatch_mm = 0.0;        ///< of the best iterate
  int best_iteration = -1;
  /// The naive reversal: X_0 per model node (mm), and its mismatch when its forward solve converged.
  std::vector<Eigen::Vector3d> naive_nodes;
  bool naive_measured = false;
  double naive_mismatch_mm = 0.0;
  SolveResult reversal;            ///< the solve of x under -g
  std::vector<ReferenceIteration> history;
  double seconds = 0.0;
};

/// Runs the iteration for `loaded` (nodes: the imaged positions x; gravity: the load they carry;
/// constraints: those of the unloading). `on_iteration` (may be empty) sees each forward solve.
ReferenceStateResult estimate_reference_state(const Model& loaded, const ReferenceStateOptions& options,
                                              const std::function<void(const ReferenceIteration&)>& on_iteration);

/// `model` with its corner nodes at `corners` (one per corner node, mm) and every tet10 midside
/// node at the midpoint of its edge.
Model with_corner_positions(const Model& model, const std::vector<Eigen::Vector3d>& corners);

}  // namespace tissuemesh
