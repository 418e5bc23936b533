#include "solver_check/linear_solver.h"

#include "core/errors.h"

#include <Eigen/SparseCholesky>
#ifdef TISSUEMESH_HAVE_CHOLMOD
#include <Eigen/CholmodSupport>
#endif

#include <chrono>
#include <cmath>

namespace tissuemesh {

using SparseMatrix = Eigen::SparseMatrix<double>;

namespace {

/// Iterations allowed with an old factorisation before factorising anew. A factorisation costs
/// ~50-100 preconditioned iterations on the demo, but slow convergence signals that K has moved
/// far from the factorised one: refactorising then also speeds up the following Newton steps.
constexpr int kMaxIterations = 25;

}  // namespace

bool cholmod_available() {
#ifdef TISSUEMESH_HAVE_CHOLMOD
  return true;
#else
  return false;
#endif
}

struct SparseSpdSolver::Impl {
  bool use_cholmod = false;
  bool have_factor = false;  ///< a factorisation of some earlier K exists
  bool exact_factor = false; ///< ... and it is of the unshifted K
#ifdef TISSUEMESH_HAVE_CHOLMOD
  Eigen::CholmodSupernodalLLT<SparseMatrix, Eigen::Lower> cholmod;
#endif
  Eigen::SimplicialLDLT<SparseMatrix, Eigen::Lower> ldlt;
  bool analysed = false;

  Eigen::VectorXd apply_factor(const Eigen::VectorXd& r) {
#ifdef TISSUEMESH_HAVE_CHOLMOD
    if (use_cholmod) return cholmod.solve(r);
#endif
    return ldlt.solve(r);
  }

  /// Factorises K (with a shift on failure for CHOLMOD); returns false when nothing works.
  bool factorise(const SparseMatrix& K, int& shifted) {
    have_factor = exact_factor = false;
#ifdef TISSUEMESH_HAVE_CHOLMOD
    if (use_cholmod) {
      if (!analysed) {
        cholmod.cholmod().print = 0;  // the library never prints: failures are reported by info()
        cholmod.analyzePattern(K);
        analysed = true;
      }
      cholmod.setShift(0.0);
      cholmod.factorize(K);
      if (cholmod.info() == Eigen::Success) return have_factor = exact_factor = true;
      // Not positive definite: the smallest shift of the ladder that factorises. A larger shift
      // than needed damps the soft modes' steps (measured: the demo's increments then stall), so
      // the ladder starts small every time although each failed try costs a factorisation.
      const double mean_diagonal = K.diagonal().cwiseAbs().mean();
      for (double sigma = 1e-8; sigma <= 1e-2; sigma *= 100.0) {
        cholmod.setShift(sigma * mean_diagonal);
        cholmod.factorize(K);
        if (cholmod.info() == Eigen::Success) {
          ++shifted;
          return have_factor = true;
        }
      }
      return false;
    }
#endif
    (void)shifted;
    if (!analysed) {
      ldlt.analyzePattern(K);
      analysed = true;
    }
    ldlt.factorize(K);
    return have_factor = exact_factor = ldlt.info() == Eigen::Success;
  }

  /// Preconditioned conjugate gradients on K (lower triangle) from x = 0; true when
  /// ||K x - b|| <= rtol ||b||. Stops (false) on a direction of non-positive curvature: K is then
  /// not positive definite and the caller uses a (shifted) factorisation instead.
  bool pcg(const SparseMatrix& K, const Eigen::VectorXd& b, Eigen::VectorXd& x, double rtol, int max_iterations,
           int& iterations) {
    const auto A = K.selfadjointView<Eigen::Lower>();
    const double target = rtol * b.norm();
    x = Eigen::VectorXd::Zero(b.size());
    Eigen::VectorXd r = b, z = apply_factor(r), p = z, Ap(b.size());
    double rz = r.dot(z);
    for (int k = 0; k < max_iterations; ++k) {
      if (r.norm() <= target) return true;
      Ap.noalias() = A * p;
      const double pAp = p.dot(Ap);
      if (!(pAp > 0.0) || !std::isfinite(rz)) return false;
      const double alpha = rz / pAp;
      x += alpha * p;
      r -= alpha * Ap;
      ++iterations;
      z = apply_factor(r);
      const double rz_next = r.dot(z);
      p = z + (rz_next / rz) * p;
      rz = rz_next;
    }
    return r.norm() <= target && x.allFinite();
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

bool SparseSpdSolver::solve(const SparseMatrix& K, const Eigen::VectorXd& b, Eigen::VectorXd& x, double rtol) {
  if (b.size() == 0) {
    x.resize(0);
    return true;
  }
  // 1. The kept factorisation as preconditioner.
  if (impl_->have_factor && impl_->pcg(K, b, x, rtol, kMaxIterations, iterations_)) return true;
  // 2. A new factorisation.
  const auto start = std::chrono::steady_clock::now();
  const bool factorised = impl_->factorise(K, shifted_);
  factorisation_seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (!factorised) return false;
  ++factorisations_;
  if (impl_->exact_factor) {
    x = impl_->apply_factor(b);
    return x.allFinite();
  }
  // 3. Shifted: CG on the true K if it gets there, else the shifted (damped, energy-descending) step.
  if (impl_->pcg(K, b, x, rtol, 2 * kMaxIterations, iterations_)) return true;
  x = impl_->apply_factor(b);
  return x.allFinite();
}

}  // namespace tissuemesh
