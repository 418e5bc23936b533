// Uncoupled Ogden with the Abaqus volumetric term:
//   W = sum_i 2 mu_i / alpha_i^2 (λ̄1^alpha_i + λ̄2^alpha_i + λ̄3^alpha_i - 3) + K/2 (J - 1)^2.
//
// The isochoric part is a symmetric function of the principal values c_a of C and has no compact
// invariant form, so it is evaluated spectrally (Simo & Taylor 1991, CMAME 85:273; Miehe 1993,
// CMAME 108:351). With C = sum_a c_a N_a N_a^T and s_a = 2 dW/dc_a:
//   S     = sum_a s_a N_a N_a^T
//   dS/dC = sum_ab (ds_a/dc_b) N_a(x)N_a(x)N_b(x)N_b
//         + sum_{a!=b} gamma_ab 1/2 (N_a(x)N_b(x)N_a(x)N_b + N_a(x)N_b(x)N_b(x)N_a)
//   gamma_ab = (s_a - s_b) / (c_a - c_b), CC = 2 dS/dC.
// The first sum is the change of the principal stresses, the second the rotation of the principal
// directions (dN_a = sum_{b!=a} N_b (N_b.dC.N_a) / (c_a - c_b)).
//
// Principal derivatives, one term (mu, alpha), with e_a = λ̄_a^alpha, ē = e_1 + e_2 + e_3:
//   λ̄_a = J^-1/3 c_a^1/2, J = (c1 c2 c3)^1/2  =>  d ln e_a / dc_b = alpha/2 (δ_ab - 1/3) / c_b
//   s_a        = 2 mu / alpha (e_a - ē/3) / c_a
//   ds_a/dc_b  = mu / (c_a c_b) (e_a (δ_ab - 1/3) - (e_b - ē/3) / 3) - δ_ab s_a / c_a
// (symmetric in a, b, as a Hessian must be). alpha = 2 gives the uncoupled neo-Hookean with
// C10 = mu/2, alpha = -2 the Mooney-Rivlin with C01 = mu/2 (both tested).
//
// The volumetric part K J (J - 1) C^-1 and its tangent are the closed forms of mooney_rivlin.cpp:
// exact, no eigen-decomposition, and gamma_ab then carries only the isochoric s_a. That matters
// because K/mu is 100-1000 for tissue and the round-off of gamma grows with |s_a|.
#include "core/errors.h"
#include "materials/hyperelastic_law.h"
#include "materials/tensor4.h"

#include <Eigen/Eigenvalues>
#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

namespace tissuemesh {

namespace {

// Relative eigenvalue gap |c_a - c_b| / max(c_a, c_b) below which gamma_ab is taken from its
// limit instead of the difference quotient. The quotient loses ~eps / gap relative accuracy to
// cancellation (s_a and s_b agree to ~gap); the limit, evaluated symmetrically (principal_gamma),
// is off by O(gap^2) because it and gamma are both even in the gap about the mid-point. The two
// errors balance at gap^3 ~ eps, i.e. gap ~ cbrt(2.2e-16) = 6e-6, where the two branches agree to
// ~1e-11 of |CC| (~1e-10 for alpha = -10); a threshold ten times smaller or larger loses one to two
// digits (tests/materials/test_ogden.cpp sweeps gaps 0 to 1e-1).
constexpr double kCoincidentGap = 6e-6;

struct Term {
  double mu, alpha;
};

class UncoupledOgden : public HyperelasticLaw {
 public:
  UncoupledOgden(std::vector<Term> terms, double K) : terms_(std::move(terms)), k_(K) {}

  std::string name() const override {
    return "uncoupled Ogden ((J-1)^2, N=" + std::to_string(terms_.size()) + ")";
  }

  double energy(const Eigen::Matrix3d& C) const override {
    const Principal p(C);
    double W = 0.0;
    for (const Term& t : terms_) {
      const Eigen::Vector3d e = p.stretch_powers(t.alpha);
      W += 2.0 * t.mu / (t.alpha * t.alpha) * (e.sum() - 3.0);
    }
    const double J = std::sqrt(C.determinant());
    return W + 0.5 * k_ * (J - 1.0) * (J - 1.0);
  }

  Eigen::Matrix3d pk2(const Eigen::Matrix3d& C) const override {
    const Principal p(C);
    const Eigen::Vector3d s = principal_stress(p);
    const Eigen::Matrix3d S = p.N * s.asDiagonal() * p.N.transpose();
    const double J = std::sqrt(C.determinant());
    return S + k_ * J * (J - 1.0) * C.inverse();
  }

  Tangent6 tangent(const Eigen::Matrix3d& C) const override {
    using tensor4::kVoigt;
    const Principal p(C);
    const Eigen::Vector3d s = principal_stress(p);
    Eigen::Matrix3d H = Eigen::Matrix3d::Zero();  // H(a, b) = ds_a / dc_b
    for (const Term& t : terms_) {
      const Eigen::Vector3d e = p.stretch_powers(t.alpha);
      const double ebar3 = e.sum() / 3.0;
      for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b) {
          const double kron = a == b ? 1.0 : 0.0;
          H(a, b) += t.mu / (p.c(a) * p.c(b)) * (e(a) * (kron - 1.0 / 3.0) - (e(b) - ebar3) / 3.0);
        }
    }
    for (int a = 0; a < 3; ++a) H(a, a) -= s(a) / p.c(a);

    Tangent6 T = Tangent6::Zero();
    Eigen::Matrix3d M[3];
    for (int a = 0; a < 3; ++a) M[a] = p.N.col(a) * p.N.col(a).transpose();
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) T += 2.0 * H(a, b) * tensor4::outer(M[a], M[b]);
    // Rotation of the principal directions: 2 * gamma_ab * 1/2 (...), summed over ordered a != b
    // (the (b, a) term supplies the ij-symmetric half).
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) {
        if (a == b) continue;
        const double g = principal_gamma(p, s, H, a, b);
        const Eigen::Vector3d Na = p.N.col(a), Nb = p.N.col(b);
        for (int r = 0; r < 6; ++r)
          for (int q = 0; q < 6; ++q) {
            const int i = kVoigt[r][0], j = kVoigt[r][1], k = kVoigt[q][0], l = kVoigt[q][1];
            T(r, q) += g * Na(i) * Nb(j) * (Na(k) * Nb(l) + Nb(k) * Na(l));
          }
      }

    // Volumetric part, closed form: 2 d/dC of K (J^2 - J) C^-1.
    const Eigen::Matrix3d Ci = C.inverse();
    const double J = std::sqrt(C.determinant());
    T += k_ * ((2.0 * J - 1.0) * J * tensor4::outer(Ci, Ci) - 2.0 * (J * J - J) * tensor4::sym_product(Ci));
    return T;
  }
  Volumetric volumetric(double J) const override {
    return {0.5 * k_ * (J - 1.0) * (J - 1.0), k_ * (J - 1.0), k_};
  }

 private:
  // Principal values c (ascending) and orthonormal directions N (columns) of C.
  struct Principal {
    explicit Principal(const Eigen::Matrix3d& C) {
      // The iterative QR solver, not computeDirect: Eigen documents the closed-form cubic as less
      // accurate, and its loss is worst where two eigenvalues (nearly) coincide (uniaxial states).
      const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(C);
      c = es.eigenvalues();
      N = es.eigenvectors();
      const Eigen::Vector3d lnc = c.array().log();
      dev_ln = lnc.array() - lnc.mean();  // ln λ̄_a^2 = ln c_a - ln J^(2/3)
    }
    // e_a = λ̄_a^alpha = exp(alpha/2 (ln c_a - mean ln c)): only the deviatoric logs enter, and
    // e_a = 1 exactly at C = I (the reference state is stress-free to the last bit).
    Eigen::Vector3d stretch_powers(double alpha) const { return (0.5 * alpha * dev_ln.array()).exp(); }
    Eigen::Vector3d c, dev_ln;
    Eigen::Matrix3d N;
  };

  Eigen::Vector3d principal_stress(const Principal& p) const {
    Eigen::Vector3d s = Eigen::Vector3d::Zero();
    for (const Term& t : terms_) {
      const Eigen::Vector3d e = p.stretch_powers(t.alpha);
      s += (2.0 * t.mu / t.alpha) * (e.array() - e.sum() / 3.0).matrix().cwiseQuotient(p.c);
    }
    return s;
  }

  // gamma_ab = (s_a - s_b) / (c_a - c_b), or its limit ds_a/dc_a - ds_a/dc_b for coincident
  // eigenvalues. The limit is averaged over a <-> b, 1/2 (H_aa - 2 H_ab + H_bb): symmetric in a, b
  // (keeps CC major-symmetric) and, like gamma itself, even in the gap, so its error is O(gap^2)
  // rather than O(gap).
  static double principal_gamma(const Principal& p, const Eigen::Vector3d& s, const Eigen::Matrix3d& H,
                                int a, int b) {
    const double gap = std::abs(p.c(a) - p.c(b));
    if (gap > kCoincidentGap * std::max(p.c(a), p.c(b))) return (s(a) - s(b)) / (p.c(a) - p.c(b));
    return 0.5 * (H(a, a) - 2.0 * H(a, b) + H(b, b));
  }

  std::vector<Term> terms_;
  double k_;
};

}  // namespace

std::unique_ptr<HyperelasticLaw> make_uncoupled_ogden(const std::vector<double>& mu,
                                                      const std::vector<double>& alpha, double K) {
  if (mu.size() != alpha.size())
    throw InputError("Ogden law: " + std::to_string(mu.size()) + " mu values but " +
                     std::to_string(alpha.size()) + " alpha values");
  if (mu.empty() || mu.size() > 3)
    throw InputError("Ogden law: 1 to 3 terms supported, got " + std::to_string(mu.size()));
  std::vector<Term> terms;
  for (std::size_t i = 0; i < mu.size(); ++i) {
    // alpha = 0 makes 2 mu / alpha^2 infinite (the term degenerates to a log law, not supported).
    if (alpha[i] == 0.0) throw InputError("Ogden law: term " + std::to_string(i + 1) + " has alpha = 0");
    terms.push_back({mu[i], alpha[i]});
  }
  return std::make_unique<UncoupledOgden>(std::move(terms), K);
}

}  // namespace tissuemesh
