// Why: a factorisation is the expensive part of a Newton iteration (the demo's tet4 tangent: 60K
// unknowns, 18 GFlop), and the tangent changes little between Newton iterations and increments.
// So a factorisation is kept and preconditions conjugate gradients on the current K: CG typically
// reaches the requested accuracy in a few iterations, each costing one multiplication by K and
// one pair of triangular solves, a small fraction of a factorisation. In single precision on two
// threads (single_precision_factor.h) the preconditioner streams half the bytes, two subtrees at
// once. The numeric factorisations are SupernodalCholesky's (supernodal_cholesky.h), about twice
// as fast as CHOLMOD's own on two threads, with the same Newton path. When K is not positive
// definite, a shifted factorisation gives a damped step instead of failing; how the shift is
// chosen is documented at kEstimateMargin, Impl::sigma_start and Impl::factorise below.
#include "solver_check/linear_solver.h"

#include "core/errors.h"
#include "solver_check/single_precision_factor.h"
#include "solver_check/supernodal_cholesky.h"

#include <Eigen/Eigenvalues>
#include <Eigen/SparseCholesky>
#ifdef TISSUEMESH_HAVE_CHOLMOD
#include "solver_check/cholmod_llt.h"
#endif

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <exception>
#include <stdexcept>
#include <string>

namespace tissuemesh {

using SparseMatrix = Eigen::SparseMatrix<double>;

namespace {

/// Iterations allowed with an old factorisation before factorising anew. A factorisation costs
/// some 15-30 preconditioned iterations on the phantom models, and slow convergence signals that
/// K has moved far from the factorised one: refactorising then also speeds up the following
/// Newton steps (kAgedShare refactorises earlier still).
constexpr int kMaxIterations = 25;

/// When the last CG solve on the kept factor took more than kAgedShare of a factorisation's cost
/// (counted in CG iterations), the factor has aged: the next solve factorises straight away (CG's
/// counts grow as the tangent moves away from the factorised one, and a new factor makes the
/// following solves short again: a few more factorisations buy half the CG iterations and a
/// shorter solve, without lengthening the Newton path). The cost of a factorisation in CG
/// iterations is estimated from the symbolic analysis' counts, so the rule is deterministic:
/// factor_flops / (kFlopsPerStreamedEntry x factor_entries), the ratio of a factorisation's flop
/// rate (~35 GFlop/s) to the single-precision solves' streaming rate (~9 GB/s, 4-byte entries read
/// twice per iteration) on a 2-core machine; the estimate is a little above the iterations a
/// factorisation really costs. For small factors it is below one iteration, so any CG solve ages
/// them. CHOLMOD only (Eigen's LDLT counts no flops).
constexpr double kFlopsPerStreamedEntry = 31.0;
constexpr double kAgedShare = 0.5;

/// First shift tried for a tangent that CG proved indefinite: kEstimateMargin x |rho|, rho the
/// Rayleigh quotient LOBPCG reaches for K's lowest eigenvalue (lowest_eigenvalue below). rho never
/// lies below the lowest eigenvalue lambda_min and approaches it from above, so |rho| <= |lambda_min|:
/// the margin covers the estimate's shortfall (LOBPCG stops once rho changes by less than
/// kEigenChange per iteration) and leaves K + sigma I a smallest eigenvalue of a few |lambda_min|, a
/// damped step. A few iterations bring rho within ~10 % of lambda_min, while CG's proven bound is
/// often several times smaller: the ladder alone would try a rung that fails (a whole
/// factorisation) and then one far above |lambda_min| (a more damped step, more Newton
/// iterations).
constexpr double kEstimateMargin = 5.0;
constexpr double kEigenChange = 0.1;
constexpr int kMaxEigenIterations = 10;

/// Diagonal shift ladder (relative to mean|K_ii|) for a tangent that is not positive definite.
constexpr double kMinShift = 1e-8;
constexpr double kMaxShift = 1e-2;
constexpr double kShiftFactor = 100.0;


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
  int threads = 1;  ///< for the single-precision preconditioner's solves
  /// For SupernodalCholesky: `threads`, or 1 when OpenBLAS runs more than one thread per call (two
  /// threads calling a multithreaded OpenBLAS at once are serialised or worse; the same bits).
  int factorisation_threads = 1;
  /// What precondition() applied last (SparseSpdSolver::preconditioner()).
  enum class Applied { None, Double, Single } applied = Applied::None;
  /// The kept factorisation is of an earlier, unshifted K: the next solve's preconditioner. A
  /// factor of a shifted K is a poor one for the next K (CG then needs more than kMaxIterations
  /// every time), so after it the next solve factorises straight away.
  bool exact_factor = false;
  /// First rung of the shift ladder (relative to mean|K_ii|): the shift that worked last time,
  /// the estimate's included, one rung lower after two unshifted factorisations in a row. A
  /// failed rung costs up to a full factorisation (CHOLMOD stops at the first non-positive pivot,
  /// often late), and the tangent's indefiniteness changes slowly along a solve; a larger shift
  /// than needed damps the soft modes' steps (the demo's increments then stall), hence the step
  /// back down. The next Newton iteration's tangent is usually still indefinite after a shift
  /// worked: a ladder restarted at kMinShift would fail rung after rung before reaching it.
  double sigma_start = kMinShift;  ///< always in [kMinShift, kMaxShift]
  bool last_shifted = false;  ///< the last factorisation was shifted
  int last_cg_iterations = 0;  ///< of the last CG solve since the last factorisation (0: none)

  /// The kept factor has aged (kAgedShare): factorise instead of iterating.
  bool factor_aged() const {
    if (!(factor_flops > 0.0 && factor_entries > 0.0)) return false;
    return last_cg_iterations > kAgedShare * factor_flops / (kFlopsPerStreamedEntry * factor_entries);
  }
#ifdef TISSUEMESH_HAVE_CHOLMOD
  CholmodLLT cholmod;
  /// The kept exact factorisation in single precision (in cholmod's own storage): CG's
  /// preconditioner (empty: use cholmod).
  SinglePrecisionFactor preconditioner;
  /// The numeric factorisation into cholmod's factor on two threads (empty: cholmod's own, when
  /// the factor's layout was refused).
  SupernodalCholesky numeric;
#endif
  Eigen::SimplicialLDLT<SparseMatrix, Eigen::Lower> ldlt;
  bool analysed = false;
  /// Group of each unknown (the constructor's `unknown_groups`; empty: no grouping).
  std::vector<int> groups;
  double analysis_seconds = 0.0;
  double factor_entries = 0.0, factor_flops = 0.0;

  Eigen::VectorXd apply_factor(const Eigen::VectorXd& r) {
#ifdef TISSUEMESH_HAVE_CHOLMOD
    if (use_cholmod) return cholmod.solve(r);
#endif
    return ldlt.solve(r);
  }

  /// After the direct solve with a new unshifted CHOLMOD factor: the factor becomes CG's
  /// single-precision preconditioner, converted in place (no memory beyond the factor's own);
  /// cholmod.solve() is not used again until the next factorisation.
  void keep_single_precision() {
#ifdef TISSUEMESH_HAVE_CHOLMOD
    if (!use_cholmod || !exact_factor || !cholmod.factor_readable()) return;
    try {
      preconditioner.assign(cholmod.factor());
    } catch (const std::exception&) {
      // Refused (or out of memory) before touching the factor: CG keeps using it in double.
      preconditioner.clear();
    }
#endif
  }

  /// CG's preconditioner: the kept factor, in single precision when it was converted.
  void precondition(const Eigen::VectorXd& r, Eigen::VectorXd& z) {
#ifdef TISSUEMESH_HAVE_CHOLMOD
    if (use_cholmod && !preconditioner.empty()) {
      applied = Applied::Single;
      return preconditioner.solve(r, z, threads);
    }
#endif
    applied = Applied::Double;
    z = apply_factor(r);
  }

#ifdef TISSUEMESH_HAVE_CHOLMOD
  /// The numeric factorisation of K + shift I into cholmod's factor: by `numeric` when planned,
  /// else by CHOLMOD. True when positive definite.
  bool factorise_shifted(const SparseMatrix& K, double shift) {
    if (!numeric.empty()) {
      const bool ok = numeric.factorise(K, shift, factorisation_threads);
      cholmod.set_factorised(ok);
      return ok;
    }
    cholmod.setShift(shift);
    cholmod.factorize(K);
    return cholmod.info() == Eigen::Success;
  }
#endif

  /// What CG found out about an indefinite K before a factorisation.
  struct Indefiniteness {
    bool known = false;            ///< CG met negative curvature: the unshifted attempt is skipped
    double proven_shift = 0.0;     ///< shifts below this must fail (CG's direction p proves it)
    double estimated_shift = 0.0;  ///< |rho| of lowest_eigenvalue (0: none)
  };

  /// Factorises K; returns false when nothing works. CHOLMOD: when K is not positive definite
  /// (CG has proved it: the unshifted attempt is skipped), first K + kEstimateMargin x
  /// estimated_shift I when there is an estimate, then the shift ladder K + sigma * mean|K_ii| I,
  /// sigma = sigma_start, 100 sigma_start, ... kMaxShift, skipping the rungs that must fail: below
  /// proven_shift (p^T (K + s I) p < 0 for every s below it) or a shift that failed already.
  bool factorise(const SparseMatrix& K, Indefiniteness indefinite, int& shifted, int& failed) {
    exact_factor = false;
#ifdef TISSUEMESH_HAVE_CHOLMOD
    preconditioner.clear();  // its values are about to be overwritten
    if (use_cholmod) {
      if (!analysed) {
        cholmod_common& c = cholmod.cholmod();
        c.print = 0;  // the library never prints: failures are reported by info()
        // Coarser supernode amalgamation than CHOLMOD's default (nrelax 4/16/48, zrelax
        // 0.8/0.1/0.05): bigger dense blocks for BLAS at the cost of a few explicit zeros. Twice
        // the default makes the numeric factorisation about a sixth faster; three times gains
        // nothing more.
        for (int i = 0; i < 3; ++i) c.nrelax[i] *= 2;
        c.zrelax[1] *= 2;
        c.zrelax[2] *= 2;
        const auto start = std::chrono::steady_clock::now();
        if (groups.empty() || !cholmod.analyse_grouped(K, groups)) {
          // CHOLMOD's own choice: AMD, and METIS when AMD's fill is high (nmethods 0).
          c.nmethods = 0;
          cholmod.analyzePattern(K);
        }
        // The numeric factorisations on two threads (supernodal_cholesky.h); CHOLMOD's own if its
        // layout is refused.
        try {
          if (cholmod.allocate_values()) numeric.plan(cholmod.factor(), K);
        } catch (const std::exception&) {
          // Refused (or out of memory) before changing `numeric`: it stays empty.
        }
        analysis_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        factor_entries = c.lnz;
        factor_flops = c.fl;
        analysed = true;
      }
      if (!indefinite.known) {
        if (factorise_shifted(K, 0.0)) {
          if (!last_shifted) sigma_start = std::max(kMinShift, sigma_start / kShiftFactor);
          last_shifted = false;
          return exact_factor = true;
        }
        ++failed;
      }
      double must_fail = indefinite.proven_shift;  // shifts up to this fail
      const double mean_diagonal = K.diagonal().cwiseAbs().mean();
      if (!(std::isfinite(mean_diagonal) && mean_diagonal > 0.0)) return false;  // no scale for a shift
      if (indefinite.estimated_shift > 0.0) {
        const double shift = std::max(kEstimateMargin * indefinite.estimated_shift, indefinite.proven_shift);
        if (factorise_shifted(K, shift)) {
          ++shifted;
          const double sigma = shift / mean_diagonal;
          if (std::isfinite(sigma)) sigma_start = std::clamp(sigma, kMinShift, kMaxShift);
          last_shifted = true;
          return true;
        }
        ++failed;
        must_fail = shift;
      }
      // sigma_start, kShiftFactor times that, ... and kMaxShift last; a rung within rounding of
      // kMaxShift is kMaxShift (1e-8 x 100^3 is 0.009999999999999998: it would be tried twice).
      for (double sigma = sigma_start;; sigma *= kShiftFactor) {
        if (sigma >= kMaxShift * (1.0 - 1e-9)) sigma = kMaxShift;
        if (sigma * mean_diagonal > must_fail) {
          if (factorise_shifted(K, sigma * mean_diagonal)) {
            ++shifted;
            sigma_start = sigma;
            last_shifted = true;
            return true;
          }
          ++failed;
        }
        if (!(sigma < kMaxShift)) return false;
      }
    }
#endif
    (void)indefinite;
    (void)shifted;
    (void)failed;
    if (!analysed) {
      ldlt.analyzePattern(K);
      analysed = true;
    }
    ldlt.factorize(K);
    if (ldlt.info() == Eigen::Success)  // the same after every factorisation (pattern fixed by the analysis)
      factor_entries = static_cast<double>(ldlt.matrixL().nestedExpression().nonZeros() + K.rows());
    return exact_factor = ldlt.info() == Eigen::Success;
  }

  /// Rayleigh quotient rho of K's lowest eigenvector, estimated by LOBPCG with block size 1
  /// (Knyazev 2001) from x (x^T K x < 0), preconditioned like CG: each iteration minimises the
  /// Rayleigh quotient over span{x, T r, previous direction}, r = K x - rho x, T the kept factor,
  /// at the cost of one multiplication by K and one preconditioner application (like a CG
  /// iteration). The basis is orthonormalised (modified Gram-Schmidt; a direction that is nearly in
  /// the span of the others is dropped), so the small eigenproblem stays well conditioned. Stops when
  /// rho changes by at most kEigenChange x |rho|, r is small (1e-2 |rho|) or after
  /// kMaxEigenIterations. Returns x^T K x / x^T x for the best x met, recomputed with a fresh
  /// multiplication: a Rayleigh quotient, so >= lambda_min up to round-off.
  double lowest_eigenvalue(const SparseMatrix& K, Eigen::VectorXd x, int& iterations) {
    const auto A = K.selfadjointView<Eigen::Lower>();
    x.normalize();
    Eigen::VectorXd Ax = A * x, p, Ap, w, r, best = x;
    double rho = x.dot(Ax), best_rho = rho;
    for (int it = 0; it < kMaxEigenIterations; ++it) {
      r = Ax - rho * x;
      if (r.norm() <= 1e-2 * std::abs(rho)) break;
      ++iterations;
      precondition(r, w);
      // Orthonormal basis of {x, w, p} with K times each column (K applied once, to w).
      Eigen::MatrixXd S(x.size(), 3), AS(x.size(), 3);
      S.col(0) = x;
      AS.col(0) = Ax;
      int m = 1;
      const auto add = [&](const Eigen::VectorXd& v, const Eigen::VectorXd& Av) {
        Eigen::VectorXd u = v, Au = Av;
        const double size = v.norm();
        for (int j = 0; j < m; ++j) {
          const double c = S.col(j).dot(u);
          u -= c * S.col(j);
          Au -= c * AS.col(j);
        }
        const double rest = u.norm();
        if (!(rest > 1e-8 * size)) return;  // (nearly) in the span already, or not finite
        S.col(m) = u / rest;
        AS.col(m) = Au / rest;
        ++m;
      };
      add(w, A * w);
      if (p.size() > 0) add(p, Ap);
      if (m == 1) break;
      // Rayleigh-Ritz: the lowest eigenpair of S^T K S (symmetrised against round-off).
      const Eigen::MatrixXd G = S.leftCols(m).transpose() * AS.leftCols(m);
      Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> ritz(0.5 * (G + G.transpose()));
      if (ritz.info() != Eigen::Success || !ritz.eigenvectors().allFinite()) break;
      const Eigen::VectorXd y = ritz.eigenvectors().col(0);
      p = S.middleCols(1, m - 1) * y.tail(m - 1);
      Ap = AS.middleCols(1, m - 1) * y.tail(m - 1);
      x = S.leftCols(m) * y;
      Ax = AS.leftCols(m) * y;
      const double norm = x.norm();
      x /= norm;
      Ax /= norm;
      const double previous = rho;
      rho = x.dot(Ax);
      if (rho < best_rho) {
        best_rho = rho;
        best = x;
      }
      if (std::abs(rho - previous) <= kEigenChange * std::abs(rho)) break;
    }
    return best.dot(A * best) / best.squaredNorm();
  }

  enum class CgOutcome { Converged, NegativeCurvature, NotConverged };

  /// Preconditioned conjugate gradients on K (lower triangle) from x = 0 until
  /// ||K x - b|| <= rtol ||b|| (Converged) or max_iterations (NotConverged). A direction p with
  /// p^T K p <= 0 proves K not positive definite: it stops there (NegativeCurvature), with
  /// proven_shift = -p^T K p / p^T p less its rounding error (K + s I is not positive definite for
  /// any s below it) and the direction in `negative`.
  CgOutcome pcg(const SparseMatrix& K, const Eigen::VectorXd& b, Eigen::VectorXd& x, double rtol,
                int max_iterations, int& iterations, double& proven_shift, Eigen::VectorXd& negative) {
    const auto A = K.selfadjointView<Eigen::Lower>();
    const double target = rtol * b.norm();
    x = Eigen::VectorXd::Zero(b.size());
    Eigen::VectorXd r = b, z, z_previous, p, Ap(b.size());
    precondition(r, z);
    p = z;
    double rz = r.dot(z);
    for (int k = 0; k < max_iterations; ++k) {
      if (r.norm() <= target) return CgOutcome::Converged;
      Ap.noalias() = A * p;
      const double pAp = p.dot(Ap);
      if (!std::isfinite(rz) || !std::isfinite(pAp)) return CgOutcome::NotConverged;
      if (!(pAp > 0.0)) {
        // Less the rounding error bound of p^T K p (n eps |p|^T |K| |p|), so a rung is skipped
        // only when its failure is certain.
        const Eigen::VectorXd abs_p = p.cwiseAbs();
        const SparseMatrix abs_K = K.cwiseAbs();
        const double rounding = static_cast<double>(K.rows()) * std::numeric_limits<double>::epsilon() *
                                abs_p.dot(abs_K.selfadjointView<Eigen::Lower>() * abs_p);
        proven_shift = std::max(0.0, (-pAp - rounding) / p.squaredNorm());
        negative = p;
        return CgOutcome::NegativeCurvature;
      }
      const double alpha = rz / pAp;
      x += alpha * p;
      r -= alpha * Ap;
      ++iterations;
      z_previous.swap(z);
      precondition(r, z);
      // Polak-Ribiere's beta (flexible CG): a preconditioner rounded to single precision is not
      // exactly a fixed symmetric operator, and this form keeps CG converging regardless.
      const double rz_next = r.dot(z);
      p = z + ((rz_next - r.dot(z_previous)) / rz) * p;
      rz = rz_next;
    }
    return r.norm() <= target && x.allFinite() ? CgOutcome::Converged : CgOutcome::NotConverged;
  }
};

SparseSpdSolver::SparseSpdSolver(LinearSolverKind kind, int threads, std::vector<int> unknown_groups)
    : impl_(std::make_unique<Impl>()) {
  impl_->threads = std::max(1, threads);
  for (std::size_t j = 0; j < unknown_groups.size(); ++j) {
    const int previous = j == 0 ? -1 : unknown_groups[j - 1];
    if (unknown_groups[j] != previous && unknown_groups[j] != previous + 1)
      throw std::invalid_argument("SparseSpdSolver: unknown groups must be numbered 0, 1, ... without gaps or "
                                  "decreases (unknown " + std::to_string(j) + ")");
  }
  impl_->groups = std::move(unknown_groups);
  if (kind == LinearSolverKind::Cholmod && !cholmod_available())
    throw SolverError("linear solver CHOLMOD requested, but this build has no CHOLMOD (install libsuitesparse-dev "
                      "and rebuild)");
  impl_->use_cholmod = kind != LinearSolverKind::SimplicialLDLT && cholmod_available();
#ifdef TISSUEMESH_HAVE_CHOLMOD
  if (impl_->use_cholmod) {
    fix_blas_threads();
    impl_->factorisation_threads = blas_threads() > 1 ? 1 : impl_->threads;
  }
#endif
}

SparseSpdSolver::~SparseSpdSolver() = default;

double SparseSpdSolver::factor_entries() const { return impl_->factor_entries; }
double SparseSpdSolver::factor_flops() const { return impl_->factor_flops; }
void SparseSpdSolver::forget_factorisation() {
  impl_->exact_factor = false;
  impl_->sigma_start = kMinShift;
  impl_->last_shifted = false;
  impl_->last_cg_iterations = 0;
}

double SparseSpdSolver::analysis_seconds() const { return impl_->analysis_seconds; }

std::vector<int> SparseSpdSolver::ordering() const {
#ifdef TISSUEMESH_HAVE_CHOLMOD
  if (impl_->use_cholmod && impl_->analysed) return impl_->cholmod.ordering();
#endif
  return {};
}

std::string SparseSpdSolver::preconditioner() const {
  switch (impl_->applied) {
    case Impl::Applied::Single:
      return "the kept factorisation in single precision, " + std::to_string(impl_->threads) +
             (impl_->threads == 1 ? " thread" : " threads");
    case Impl::Applied::Double:
      return "the kept factorisation";
    case Impl::Applied::None:
      break;
  }
  return "none";
}

std::string SparseSpdSolver::numeric_factorisation() const {
  if (!impl_->analysed) return "none";
#ifdef TISSUEMESH_HAVE_CHOLMOD
  if (impl_->use_cholmod && !impl_->numeric.empty()) {
    const SupernodalCholesky& numeric = impl_->numeric;
    if (impl_->factorisation_threads == 1) return "SupernodalCholesky, 1 thread";
    if (numeric.top_share() >= 1.0)
      return numeric.panelled() ? "SupernodalCholesky, 2 threads (the tree does not split: its wide supernodes by "
                                  "panels on two, the rest on one)"
                                : "SupernodalCholesky, 1 thread (the tree does not split)";
    const int top = static_cast<int>(std::lround(100.0 * numeric.top_share()));
    return "SupernodalCholesky, 2 threads (two subtrees at once, then the top separators, " + std::to_string(top) +
           " % of the flops" + (numeric.panelled() ? ": the wide ones by panels on two)" : ", on one)");
  }
  if (impl_->use_cholmod) return "CHOLMOD";
#endif
  return "Eigen";
}

std::string SparseSpdSolver::name() const {
  return impl_->use_cholmod ? "CHOLMOD supernodal LLT" : "Eigen SimplicialLDLT";
}

bool SparseSpdSolver::solve(const SparseMatrix& K, const Eigen::VectorXd& b, Eigen::VectorXd& x, double rtol) {
  if (b.size() == 0) {
    x.resize(0);
    return true;
  }
  // 1. The kept factorisation of an unshifted K as preconditioner, unless it has aged (the last
  // CG solve was long: kAgedShare). Negative curvature proves K indefinite: the factorisation
  // below then goes straight to a shift, estimated from K's lowest eigenvalue (with CHOLMOD,
  // whose shifted factorisation can fail).
  Impl::Indefiniteness indefinite;
  if (impl_->exact_factor && !impl_->factor_aged()) {
    Eigen::VectorXd negative;
    const int before = iterations_;
    const Impl::CgOutcome outcome =
        impl_->pcg(K, b, x, rtol, kMaxIterations, iterations_, indefinite.proven_shift, negative);
    impl_->last_cg_iterations = iterations_ - before;
    if (outcome == Impl::CgOutcome::Converged) return true;
    indefinite.known = outcome == Impl::CgOutcome::NegativeCurvature;
    if (indefinite.known && impl_->use_cholmod) {
      const double rho = impl_->lowest_eigenvalue(K, negative, eigenvalue_iterations_);
      if (std::isfinite(rho) && rho < 0.0) indefinite.estimated_shift = -rho;
    }
  }
  // 2. A new factorisation.
  const auto start = std::chrono::steady_clock::now();
  const double analysed_before = impl_->analysis_seconds;
  const bool factorised = impl_->factorise(K, indefinite, shifted_, failed_);
  factorisation_seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() -
                            (impl_->analysis_seconds - analysed_before);
  if (!factorised) return false;
  impl_->last_cg_iterations = 0;
  ++factorisations_;
  // 3. The direct solve; with a shifted factor (K is not positive definite) the damped step.
  x = impl_->apply_factor(b);
  impl_->keep_single_precision();
  return x.allFinite();
}

}  // namespace tissuemesh
