// CholmodLLT: Eigen's CHOLMOD supernodal LL' wrapper with the additions the built-in solver's
// SparseSpdSolver (linear_solver.h) needs: its factor readable in place (for SupernodalCholesky and
// the single-precision preconditioner), a symbolic analysis ordered by METIS on the graph of the
// unknowns' groups, and a fixed OpenBLAS thread count. Internal to solver_check (not installed):
// compiled only when the build has CHOLMOD (TISSUEMESH_HAVE_CHOLMOD).
#pragma once

#include "solver_check/supernodal_tree.h"

#include <Eigen/CholmodSupport>
#include <Eigen/SparseCore>

#include <vector>

namespace tissuemesh {

/// Eigen's CHOLMOD wrapper, with its factor readable (for the single-precision preconditioner).
class CholmodLLT : public Eigen::CholmodSupernodalLLT<Eigen::SparseMatrix<double>, Eigen::Lower> {
 public:
  /// The supernodal LL' factor of the last successful factorize() (CHOLMOD's int layout).
  /// SinglePrecisionFactor::assign() converts its values in place: solve() must not be called
  /// after that until the next factorize(), which overwrites every value.
  SupernodalFactorView factor() {
    const cholmod_factor& L = *m_cholmodFactor;
    SupernodalFactorView v;
    v.n = static_cast<int>(L.n);
    v.nsuper = static_cast<int>(L.nsuper);
    v.super = static_cast<const int*>(L.super);
    v.pi = static_cast<const int*>(L.pi);
    v.px = static_cast<const int*>(L.px);
    v.rows = static_cast<const int*>(L.s);
    v.values = static_cast<double*>(L.x);
    v.perm = static_cast<const int*>(L.Perm);
    return v;
  }
  /// Symbolic analysis of K (lower triangle) with METIS nested dissection computed on the graph of
  /// the unknowns' groups (`group`: SparseSpdSolver's constructor) instead of on K's own graph; each
  /// group's unknowns stay together, in their order. False (nothing changed) when METIS fails.
  bool analyse_grouped(const Eigen::SparseMatrix<double>& K, const std::vector<int>& group);
  /// The fill-reducing permutation of the analysis: row k of L is unknown ordering()[k].
  std::vector<int> ordering() const {
    const int* perm = static_cast<const int*>(m_cholmodFactor->Perm);
    return std::vector<int>(perm, perm + m_cholmodFactor->n);
  }
  /// Gives the analysed (symbolic) factor its numeric storage, for SupernodalCholesky to fill;
  /// false when CHOLMOD refuses (out of memory) or the result is not readable by factor().
  bool allocate_values() {
    return cholmod_change_factor(CHOLMOD_REAL, 1, 1, 1, 1, m_cholmodFactor, &this->cholmod()) && factor_readable();
  }
  /// Marks the factor as factorised by SupernodalCholesky (ok), or failed, as factorize() would.
  void set_factorised(bool ok) {
    m_cholmodFactor->minor = ok ? m_cholmodFactor->n : 0;
    m_factorizationIsOk = true;
    this->m_info = ok ? Eigen::Success : Eigen::NumericalIssue;
  }
  /// True when factor() can be read: supernodal LL', real, int indices.
  bool factor_readable() const {
    const cholmod_factor* L = m_cholmodFactor;
    return L && L->is_super && L->is_ll && L->xtype == CHOLMOD_REAL && L->itype == CHOLMOD_INT &&
           L->dtype == CHOLMOD_DOUBLE;
  }
};

/// OpenBLAS's thread count (1 for another BLAS, where the call runs on the caller's thread).
int blas_threads();
/// Sets OpenBLAS to kBlasThreads (cholmod_llt.cpp says why) unless $OPENBLAS_NUM_THREADS is set;
/// another BLAS is left alone (the functions are looked up at run time).
void fix_blas_threads();

}  // namespace tissuemesh
