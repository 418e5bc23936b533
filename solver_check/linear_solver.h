// SparseSpdSolver: the linear solver of the built-in Newton iterations (issue #4).
//
// Solves K x = b for the symmetric reduced tangent K, given by its lower triangle (column-major
// Eigen::SparseMatrix with a pattern that stays the same for a whole solve). The fill-reducing
// ordering and symbolic factorisation are computed on the first call and reused by every later
// factorisation (the pattern must not change in between).
//   Cholmod         CHOLMOD supernodal Cholesky (Eigen::CholmodSupernodalLLT; SuiteSparse's own
//                   AMD/METIS ordering; BLAS-3 on supernodes)
//   SimplicialLDLT  Eigen's sparse LDL^T (AMD ordering), also used for a tangent CHOLMOD finds
//                   not positive definite (an unstable material state: LDL^T has no square roots)
// solve() returns false (never throws) when the factorisation fails or the result is not finite.
#pragma once

#include "solver_check/static_solver.h"

#include <Eigen/SparseCore>

#include <memory>
#include <string>

namespace tissuemesh {

class SparseSpdSolver {
 public:
  /// Auto = Cholmod when available. Throws SolverError for Cholmod in a build without it.
  explicit SparseSpdSolver(LinearSolverKind kind);
  ~SparseSpdSolver();
  SparseSpdSolver(const SparseSpdSolver&) = delete;
  SparseSpdSolver& operator=(const SparseSpdSolver&) = delete;

  /// Factorises K (lower triangle) and solves K x = b.
  bool solve(const Eigen::SparseMatrix<double>& K, const Eigen::VectorXd& b, Eigen::VectorXd& x);

  /// "CHOLMOD supernodal LLT" or "Eigen SimplicialLDLT" (the primary method).
  std::string name() const;
  /// Factorisations that fell back to LDL^T because CHOLMOD found K not positive definite.
  int indefinite_fallbacks() const { return fallbacks_; }

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  int fallbacks_ = 0;
};

}  // namespace tissuemesh
