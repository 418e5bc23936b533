// SparseSpdSolver: the linear solver of the built-in Newton iterations (issue #4).
//
// Solves K x = b for the symmetric reduced tangent K, given by its lower triangle (column-major
// Eigen::SparseMatrix whose pattern stays the same for a whole solve). The fill-reducing ordering
// and symbolic factorisation are computed once and reused by every factorisation.
//
// A factorisation is the expensive part (the demo's tet4 tangent: 60K unknowns, 18 GFlop), and the
// tangent changes little between Newton iterations and increments. So a factorisation is kept and
// used as the preconditioner of conjugate gradients on the current K; CG typically reaches the
// requested accuracy in a few iterations, each costing one multiplication by K and one pair of
// triangular solves (~1/14 of a factorisation on the 60K-tet benchmark model, ~1/27 on the demo).
// K is factorised anew and solved directly when CG needs more than 25 iterations or meets
// non-positive curvature, and straight away when the last CG solve took more than half a
// factorisation's cost, estimated as factor_flops() / (31 factor_entries()) iterations with
// CHOLMOD (the factor has aged; linear_solver.cpp, kAgedShare, says why; for small factors the
// estimate is below one iteration, so any CG solve ages them). With CHOLMOD, CG applies the kept
// factor converted to single precision, on two threads (solver_check/single_precision_factor.h:
// half the bytes to stream, two subtrees at once; on the benchmark model 4.2 ms per application
// instead of ~10 ms); the direct solves use the factor itself. The answer is the same up to the
// requested relative residual ||K x - b|| <= rtol ||b|| (the Newton loop's inexactness), except
// for a K that is not positive definite (below).
//   Cholmod         CHOLMOD's supernodal Cholesky (Eigen::CholmodSupernodalLLT; METIS on the
//                   graph of the unknown groups when given, else CHOLMOD's own AMD/METIS choice;
//                   supernodes amalgamated twice as coarsely as its default). CHOLMOD analyses
//                   and solves; the numeric factorisations into its factor are
//                   SupernodalCholesky's (supernodal_cholesky.h: two subtrees on two threads;
//                   CHOLMOD's own if the factor's layout is refused). Measured on the 60K-tet
//                   benchmark model: 5 factorisations 0.74-0.89 s instead of 1.71-1.85 s with
//                   CHOLMOD's, the same Newton path. A K that is not positive definite (soft
//                   tissue in compression, far from equilibrium: CG met negative curvature, or
//                   CHOLMOD found a non-positive pivot) is factorised with a diagonal shift, and
//                   that factor's solution is the step (a damped, energy-descending step as in
//                   Levenberg-Marquardt). When CG met negative curvature along p, a few LOBPCG
//                   iterations from p (preconditioned by the kept factor) estimate K's lowest
//                   eigenvalue lambda_min, and the shift is 5 |rho| (rho: the estimate's Rayleigh
//                   quotient, |rho| <= |lambda_min|; at least CG's proven bound below); if that
//                   fails, or without an estimate (no kept factor, or an aged one: CG did not
//                   run, and the unshifted attempt is what finds K indefinite), the shift is
//                   sigma * mean|K_ii|, sigma on a ladder of factors of 100 that ends at 1e-2.
//                   The ladder starts at the shift that succeeded last, the estimate's included
//                   (clamped to [1e-8, 1e-2]; 1e-8 before any shift), one rung lower after two
//                   unshifted factorisations in a row (each failed rung costs up to a
//                   factorisation), tries each rung once, and skips the rungs that must fail:
//                   below -p^T K p / p^T p, which K + s I cannot survive, or at most a shift that
//                   failed. A shifted factor is not kept as the next preconditioner.
//   SimplicialLDLT  Eigen's sparse LDL^T (AMD ordering); copes with an indefinite K directly.
// solve() returns false (never throws) when nothing gives a finite solution.
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
  /// group's unknowns kept together (a supervariable). Measured on the 60K-tet benchmark model
  /// (41,541 unknowns): analysis 0.15-0.16 s instead of 0.24-0.28 s (CHOLMOD's own choice,
  /// METIS on the unknowns' graph: 9x the edges), 3.83 instead of 4.16 GFlop per factorisation
  /// (7.73M instead of 7.96M factor entries). Without groups, or if METIS fails: CHOLMOD's own choice.
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
