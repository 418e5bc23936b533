// SparseSpdSolver: the linear solver of the built-in Newton iterations (docs/solver.md, "Linear
// solvers").
//
// Solves K x = b for the symmetric reduced tangent K, given by its lower triangle (column-major
// Eigen::SparseMatrix whose pattern stays the same for a whole solve), to the relative residual
// ||K x - b|| <= rtol ||b|| (the Newton loop's inexactness). The ordering and symbolic analysis are
// computed once. A factorisation is kept and preconditions conjugate gradients on later tangents;
// K is factorised anew and solved directly when CG needs more than 25 iterations, meets
// non-positive curvature, or (CHOLMOD) the last CG solve cost more than half a factorisation
// (estimated from factor_flops() and factor_entries(); the .cpp says why).
//   Cholmod         CHOLMOD's supernodal Cholesky (Chen, Davis, Hager & Rajamanickam, ACM TOMS
//                   35, 2008) analyses (METIS on the graph of the unknown groups when given, else
//                   CHOLMOD's own choice) and solves; the numeric factorisations into its factor
//                   are SupernodalCholesky's (CHOLMOD's own if the layout is refused); CG applies
//                   the kept factor in single precision (SinglePrecisionFactor). A K that is not
//                   positive definite is factorised with a diagonal shift (estimated by LOBPCG
//                   when CG met negative curvature, else a ladder from 1e-8 to 1e-2 of
//                   mean|K_ii|), and that factor's solution is returned: a damped,
//                   energy-descending step as in Levenberg-Marquardt, not the solution of K x = b.
//   SimplicialLDLT  Eigen's sparse LDL^T (AMD ordering); copes with an indefinite K directly.
// The result does not depend on `threads`. solve() returns false (never throws) when nothing
// gives a finite solution.
#pragma once

#include "solver_check/static_solver.h"

#include <Eigen/SparseCore>

#include <memory>
#include <string>
#include <vector>

namespace tissuemesh {

class SparseSpdSolver {
 public:
  /// Auto = Cholmod when available. Throws SolverError for Cholmod in a build without it.
  /// `unknown_groups`: empty, or one group id per unknown, numbered 0, 1, ... in unknown order (a
  /// node's unknowns: DofMap::node_groups()), else std::invalid_argument. With CHOLMOD the
  /// fill-reducing ordering is then METIS nested dissection on the graph of the groups, each
  /// group's unknowns kept together (a supervariable): a faster analysis and a slightly cheaper
  /// factor than METIS on the unknowns' graph, which has 9x the edges. Without groups, or if METIS
  /// fails: CHOLMOD's own choice.
  /// `threads`: for the preconditioner's triangular solves. With CHOLMOD on OpenBLAS, sets
  /// OpenBLAS to 1 thread (process-wide) unless $OPENBLAS_NUM_THREADS is set: its thread count
  /// changes the factor's last bits (a fixed one gives the same solution on any machine), and its
  /// threads slow a factorisation many times over when other processes keep the cores busy.
  explicit SparseSpdSolver(LinearSolverKind kind, int threads = 1, std::vector<int> unknown_groups = {});
  ~SparseSpdSolver();
  SparseSpdSolver(const SparseSpdSolver&) = delete;
  SparseSpdSolver& operator=(const SparseSpdSolver&) = delete;

  /// Solves K x = b (K: lower triangle) to ||K x - b|| <= rtol ||b|` (see the header comment).
  bool solve(const Eigen::SparseMatrix<double>& K, const Eigen::VectorXd& b, Eigen::VectorXd& x, double rtol);

  /// Forgets the kept factorisation and the shift history (the analysis stays): the next solve
  /// factorises its own K, so that its result no longer depends on earlier solves.
  void forget_factorisation();

  /// "CHOLMOD supernodal LLT" or "Eigen SimplicialLDLT" (the factorisation).
  std::string name() const;
  /// Who computes the numeric factorisations: "SupernodalCholesky, 2 threads (two subtrees at
  /// once, then the top separators, N % of the flops: the wide ones by panels on two)" (", on
  /// one)" when none is wide), "SupernodalCholesky, 2 threads (the tree does not split: its wide
  /// supernodes by panels on two, the rest on one)", "SupernodalCholesky, 1 thread" (with "(the
  /// tree does not split)" when that is why), "CHOLMOD", "Eigen", or "none" before the first.
  std::string numeric_factorisation() const;
  int factorisations() const { return factorisations_; }
  int shifted_factorisations() const { return shifted_; }
  /// Factorisation attempts that found K (or K + a too small shift) not positive definite;
  /// not counted in factorisations(), but in factorisation_seconds().
  int failed_factorisations() const { return failed_; }
  int iterations() const { return iterations_; }
  /// LOBPCG iterations spent estimating the lowest eigenvalue of tangents CG proved indefinite.
  int eigenvalue_iterations() const { return eigenvalue_iterations_; }
  /// What CG was preconditioned with, e.g. "the kept factorisation in single precision, 2 threads"
  /// (whichever was used last; "none" before any CG iteration).
  std::string preconditioner() const;
  /// The fill-reducing permutation (row k of the factor is unknown ordering()[k]); empty before
  /// the first factorisation and for SimplicialLDLT.
  std::vector<int> ordering() const;
  /// Wall time of the symbolic analysis (ordering included) and of planning the numeric
  /// factorisations, once per solver.
  double analysis_seconds() const;
  /// Wall time spent in numeric factorisations (including failed attempts; not the analysis).
  double factorisation_seconds() const { return factorisation_seconds_; }
  /// Entries of the triangular factor L, diagonal included (what a factorisation stores and
  /// costs, with factor_flops()): CHOLMOD's count from the symbolic analysis, explicit zeros of
  /// amalgamated supernodes included; Eigen's the factor's nonzeros plus the diagonal. 0 before
  /// the first factorisation.
  double factor_entries() const;
  /// Floating-point operations of one numeric factorisation (CHOLMOD's count from the symbolic
  /// analysis); 0 for Eigen's SimplicialLDLT, which does not count them.
  double factor_flops() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  int factorisations_ = 0;
  int shifted_ = 0;
  int failed_ = 0;
  int iterations_ = 0;
  int eigenvalue_iterations_ = 0;
  double factorisation_seconds_ = 0.0;
};

}  // namespace tissuemesh
