#include "solver_check/linear_solver.h"

#include "core/errors.h"

#include <Eigen/SparseCholesky>
#ifdef TISSUEMESH_HAVE_CHOLMOD
#include <Eigen/CholmodSupport>
#endif

namespace tissuemesh {

using SparseMatrix = Eigen::SparseMatrix<double>;

bool cholmod_available() {
#ifdef TISSUEMESH_HAVE_CHOLMOD
  return true;
#else
  return false;
#endif
}

struct SparseSpdSolver::Impl {
  bool use_cholmod = false;
#ifdef TISSUEMESH_HAVE_CHOLMOD
  Eigen::CholmodSupernodalLLT<SparseMatrix, Eigen::Lower> cholmod;
  bool cholmod_analysed = false;
#endif
  Eigen::SimplicialLDLT<SparseMatrix, Eigen::Lower> ldlt;
  bool ldlt_analysed = false;

  bool solve_ldlt(const SparseMatrix& K, const Eigen::VectorXd& b, Eigen::VectorXd& x) {
    if (!ldlt_analysed) {
      ldlt.analyzePattern(K);
      ldlt_analysed = true;
    }
    ldlt.factorize(K);
    if (ldlt.info() != Eigen::Success) return false;
    x = ldlt.solve(b);
    return ldlt.info() == Eigen::Success && x.allFinite();
  }
};

SparseSpdSolver::SparseSpdSolver(LinearSolverKind kind) : impl_(std::make_unique<Impl>()) {
  if (kind == LinearSolverKind::Cholmod && !cholmod_available())
    throw SolverError("linear solver CHOLMOD requested, but this build has no CHOLMOD (install libsuitesparse-dev "
                      "and rebuild)");
  impl_->use_cholmod = kind != LinearSolverKind::SimplicialLDLT && cholmod_available();
}

SparseSpdSolver::~SparseSpdSolver() = default;

std::string SparseSpdSolver::name() const {
  return impl_->use_cholmod ? "CHOLMOD supernodal LLT" : "Eigen SimplicialLDLT";
}

bool SparseSpdSolver::solve(const SparseMatrix& K, const Eigen::VectorXd& b, Eigen::VectorXd& x) {
#ifdef TISSUEMESH_HAVE_CHOLMOD
  if (impl_->use_cholmod) {
    if (!impl_->cholmod_analysed) {
      impl_->cholmod.analyzePattern(K);
      impl_->cholmod_analysed = true;
    }
    impl_->cholmod.factorize(K);
    if (impl_->cholmod.info() == Eigen::Success) {
      x = impl_->cholmod.solve(b);
      if (impl_->cholmod.info() == Eigen::Success && x.allFinite()) return true;
    }
    ++fallbacks_;  // not positive definite (or a failed solve): LDL^T copes with an indefinite K
  }
#endif
  return impl_->solve_ldlt(K, b, x);
}

}  // namespace tissuemesh
