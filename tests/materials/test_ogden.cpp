// Uncoupled Ogden: stress and tangent against finite differences (generic C, C = I, two equal
// eigenvalues and a sweep of eigenvalue gaps across the coincidence threshold), the special cases
// alpha = 2 (neo-Hookean) and alpha = -2 (Mooney-Rivlin C01), additivity of terms, the reference
// state, and homogeneous uniaxial stress against a closed form and tabulated reference values
// (docs/verification.md, "Solver: analytic references").
#include "core/errors.h"
#include "materials/hyperelastic_law.h"
#include "materials/tensor4.h"
#include "support/finite_difference.h"
#include "support/tolerances.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <array>
#include <cmath>
#include <random>
#include <vector>

using namespace tissuemesh;

using test::bump;

namespace {

const Eigen::Matrix3d kI = Eigen::Matrix3d::Identity();

struct OgdenParams {
  std::vector<double> mu, alpha;
  double K;
  double shear_modulus() const {
    double s = 0.0;
    for (double m : mu) s += m;
    return s;
  }
  std::unique_ptr<HyperelasticLaw> make() const { return make_uncoupled_ogden(mu, alpha, K); }
};

// One and several terms, exponents of both signs, a large one (tissue fits often have alpha ~ 10),
// and mu_i alpha_i > 0 throughout (Ogden's stability condition).
std::vector<OgdenParams> params() {
  return {{{1.0}, {2.0}, 5.0},
          {{0.6}, {-2.0}, 4.0},
          {{0.7, 0.3}, {1.5, 5.0}, 8.0},
          {{0.8, 0.05, -0.2}, {2.5, 12.0, -3.0}, 30.0}};
}

Eigen::Matrix3d rotation() {
  return Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, -2, 3).normalized()).toRotationMatrix();
}

// C = R diag(d) R^T: principal values d along rotated (non-axis) directions.
Eigen::Matrix3d rotated_diag(double d1, double d2, double d3) {
  const Eigen::Matrix3d R = rotation();
  return R * Eigen::Vector3d(d1, d2, d3).asDiagonal() * R.transpose();
}

// Deformations with stretch, shear and volume change; fixed seed, det F kept well positive.
std::vector<Eigen::Matrix3d> random_C(int n) {
  std::mt19937 gen(20241122);
  std::uniform_real_distribution<double> u(-0.3, 0.3);
  std::vector<Eigen::Matrix3d> out;
  while (static_cast<int>(out.size()) < n) {
    Eigen::Matrix3d F = kI;
    for (int i = 0; i < 9; ++i) F(i / 3, i % 3) += u(gen);
    if (F.determinant() > 0.5) out.push_back(F.transpose() * F);
  }
  return out;
}

// The states of the finite-difference checks: generic, reference, and coincident eigenvalues
// (uniaxial tension and compression, rotated and axis-aligned), plus a gap inside the threshold.
std::vector<Eigen::Matrix3d> test_states() {
  std::vector<Eigen::Matrix3d> v = random_C(3);
  Eigen::Matrix3d F;
  F << 1.15, 0.12, -0.05, 0.03, 0.92, 0.08, -0.04, 0.06, 1.01;
  v.push_back(F.transpose() * F);
  v.push_back(kI);
  v.push_back(rotated_diag(1.3 * 1.3, 0.9 * 0.9, 0.9 * 0.9));
  v.push_back(Eigen::Vector3d(0.85 * 0.85, 1.1 * 1.1, 1.1 * 1.1).asDiagonal());
  v.push_back(rotated_diag(0.8, 1.2, 1.2 * (1.0 + 1e-7)));
  return v;
}


// Central differences, h = 1e-6 (tolerances.h, kFiniteDifferenceRel). The stress scale adds the
// shear modulus because S = 0 at C = I while its derivative is not.
void expect_stress_is_energy_gradient(const HyperelasticLaw& law, const Eigen::Matrix3d& C, double mu) {
  const double h = 1e-6;
  const Eigen::Matrix3d S = law.pk2(C);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      const double fd = 2.0 * (law.energy(bump(C, i, j, h)) - law.energy(bump(C, i, j, -h))) / (2 * h);
      EXPECT_NEAR(S(i, j), fd, test::kFiniteDifferenceRel * (S.norm() + mu)) << law.name() << " " << i << j
                                                                               << "\nC =\n" << C;
    }
}

void expect_tangent_is_stress_gradient(const HyperelasticLaw& law, const Eigen::Matrix3d& C) {
  const double h = 1e-6;
  const Tangent6 T = law.tangent(C);
  EXPECT_LT((T - T.transpose()).norm(), test::kRelativeRoundoff * T.norm()) << law.name();  // major symmetry
  for (int b = 0; b < 6; ++b) {
    const int k = tensor4::kVoigt[b][0], l = tensor4::kVoigt[b][1];
    const Eigen::Matrix3d dS = (law.pk2(bump(C, k, l, h)) - law.pk2(bump(C, k, l, -h))) / (2 * h);
    for (int a = 0; a < 6; ++a) {
      const double fd = 2.0 * dS(tensor4::kVoigt[a][0], tensor4::kVoigt[a][1]);
      EXPECT_NEAR(T(a, b), fd, test::kFiniteDifferenceRel * T.norm()) << law.name() << " " << a << b
                                                                      << "\nC =\n" << C;
    }
  }
}

// The same law by two routes: energy, stress and tangent agree to round-off (scales include the
// modulus so that the reference state, where W = S = 0, is compared meaningfully).
void expect_same_law(const HyperelasticLaw& a, const HyperelasticLaw& b, const Eigen::Matrix3d& C, double mu) {
  const double tol = test::kRelativeRoundoff;
  EXPECT_NEAR(a.energy(C), b.energy(C), tol * (std::abs(b.energy(C)) + mu)) << a.name() << " vs " << b.name();
  EXPECT_LT((a.pk2(C) - b.pk2(C)).norm(), tol * (b.pk2(C).norm() + mu)) << a.name() << " vs " << b.name();
  EXPECT_LT((a.tangent(C) - b.tangent(C)).norm(), tol * b.tangent(C).norm()) << a.name() << " vs " << b.name();
}

// Uniaxial stress: stretch lambda along x, lateral stretch s found by bisection so that S22 = 0;
// returns {P11 = lambda S11, s}.
std::array<double, 2> uniaxial(const HyperelasticLaw& law, double lambda) {
  auto C_of = [lambda](double s) { return Eigen::Matrix3d(Eigen::Vector3d(lambda * lambda, s * s, s * s).asDiagonal()); };
  double lo = 0.2, hi = 2.0;  // S22 increases with s
  for (int it = 0; it < 200; ++it) {
    const double mid = 0.5 * (lo + hi);
    (law.pk2(C_of(mid))(1, 1) > 0 ? hi : lo) = mid;
  }
  const double s = 0.5 * (lo + hi);
  return {lambda * law.pk2(C_of(s))(0, 0), s};
}

}  // namespace

TEST(OgdenLaw, StressIsTwiceTheEnergyGradient) {
  for (const auto& p : params()) {
    const auto law = p.make();
    for (const auto& C : test_states()) expect_stress_is_energy_gradient(*law, C, p.shear_modulus());
  }
}

TEST(OgdenLaw, TangentIsTwiceTheStressGradient) {
  // Includes C = I (three equal eigenvalues) and uniaxial states (two equal): the limit branch of
  // gamma_ab is what these exercise.
  for (const auto& p : params()) {
    const auto law = p.make();
    for (const auto& C : test_states()) expect_tangent_is_stress_gradient(*law, C);
  }
}

TEST(OgdenLaw, TangentIsAccurateOnBothSidesOfTheCoincidenceThreshold) {
  // Relative gaps between two eigenvalues from well separated down to exactly equal: a threshold
  // too small would show as cancellation in (s_a - s_b) / (c_a - c_b) at the small gaps, one too
  // large as the O(gap^2) error of the limit at the large gaps.
  const double gaps[] = {1e-1, 1e-2, 1e-3, 1e-4, 1e-5, 7e-6, 5e-6, 1e-6, 1e-7, 1e-8, 1e-10, 1e-12, 0.0};
  for (const auto& p : params()) {
    const auto law = p.make();
    for (double g : gaps) {
      SCOPED_TRACE("gap " + std::to_string(g));
      expect_tangent_is_stress_gradient(*law, rotated_diag(1.44, 0.81 * (1.0 + g), 0.81));
      expect_tangent_is_stress_gradient(*law, rotated_diag(0.7 * (1.0 + g), 0.7, 1.3));
    }
  }
}

TEST(OgdenLaw, AlphaTwoIsUncoupledNeoHookean) {
  // 2 mu / 4 (λ̄1^2 + λ̄2^2 + λ̄3^2 - 3) = mu/2 (Ī1 - 3): C10 = mu/2.
  const double mu = 1.7, K = 9.0;
  const auto ogden = make_uncoupled_ogden({mu}, {2.0}, K);
  const auto nh = make_uncoupled_mooney_rivlin(mu / 2, 0.0, K);
  for (const auto& C : random_C(10)) expect_same_law(*ogden, *nh, C, mu);
  expect_same_law(*ogden, *nh, kI, mu);
  expect_same_law(*ogden, *nh, rotated_diag(1.69, 0.81, 0.81), mu);
}

TEST(OgdenLaw, AlphaMinusTwoIsMooneyRivlinC01) {
  // 2 mu / 4 (λ̄1^-2 + λ̄2^-2 + λ̄3^-2 - 3) = mu/2 (Ī2 - 3), since λ̄1 λ̄2 λ̄3 = 1 makes
  // λ̄1^-2 = λ̄2^2 λ̄3^2: C10 = 0, C01 = mu/2.
  const double mu = 0.9, K = 6.0;
  const auto ogden = make_uncoupled_ogden({mu}, {-2.0}, K);
  const auto mr = make_uncoupled_mooney_rivlin(0.0, mu / 2, K);
  for (const auto& C : random_C(10)) expect_same_law(*ogden, *mr, C, mu);
  expect_same_law(*ogden, *mr, kI, mu);
  expect_same_law(*ogden, *mr, rotated_diag(0.64, 1.21, 1.21), mu);
}

TEST(OgdenLaw, TwoTermsAreTheSumOfTheirTerms) {
  // The energy is linear in (mu_i, K): splitting K between the two single-term laws must give the
  // same sum.
  const auto two = make_uncoupled_ogden({0.7, 0.3}, {1.5, -4.0}, 10.0);
  const auto a = make_uncoupled_ogden({0.7}, {1.5}, 4.0);
  const auto b = make_uncoupled_ogden({0.3}, {-4.0}, 6.0);
  const double tol = test::kRelativeRoundoff;
  std::vector<Eigen::Matrix3d> states = random_C(10);
  states.push_back(kI);
  states.push_back(rotated_diag(1.69, 0.81, 0.81));
  for (const auto& C : states) {
    EXPECT_NEAR(two->energy(C), a->energy(C) + b->energy(C), tol * (std::abs(two->energy(C)) + 1.0));
    EXPECT_LT((two->pk2(C) - a->pk2(C) - b->pk2(C)).norm(), tol * (two->pk2(C).norm() + 1.0));
    EXPECT_LT((two->tangent(C) - a->tangent(C) - b->tangent(C)).norm(), tol * two->tangent(C).norm());
  }
}

TEST(OgdenLaw, VolumetricPartIsTheEnergyOfAPureDilation) {
  // C = J^(2/3) I has unit isochoric stretches, so W = U(J) = K/2 (J - 1)^2; U' and U'' follow.
  for (const auto& p : params()) {
    const auto law = p.make();
    for (const double J : {0.9, 1.08}) {
      const HyperelasticLaw::Volumetric v = law->volumetric(J);
      EXPECT_NEAR(law->energy(std::pow(J, 2.0 / 3.0) * kI), v.U, test::kRelativeRoundoff * p.K) << law->name();
      EXPECT_NEAR(v.dU, p.K * (J - 1.0), test::kRelativeRoundoff * p.K) << law->name();
      EXPECT_NEAR(v.d2U, p.K, test::kRelativeRoundoff * p.K) << law->name();
    }
  }
}

TEST(OgdenLaw, ReferenceAndRigidRotationAreStressFree) {
  const Eigen::Matrix3d R = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d(1, 2, 2).normalized()).toRotationMatrix();
  for (const auto& p : params()) {
    const auto law = p.make();
    for (const Eigen::Matrix3d& C : {kI, Eigen::Matrix3d(R.transpose() * R)}) {
      EXPECT_NEAR(law->energy(C), 0.0, test::kRelativeRoundoff * p.shear_modulus()) << law->name();
      EXPECT_LT(law->pk2(C).norm(), test::kRelativeRoundoff * p.shear_modulus()) << law->name();
    }
  }
}

TEST(OgdenLaw, InitialTangentIsLinearElasticityWithShearModulusSumMu) {
  // At C = I, CC = lambda I(x)I + 2 mu Isym with mu = sum mu_i (Abaqus convention, material_spec.h)
  // and lambda = K - 2 mu / 3: the three-fold coincident limit of the spectral tangent.
  for (const auto& p : params()) {
    const double mu = p.shear_modulus(), lambda = p.K - 2.0 * mu / 3.0;
    const Tangent6 expected = lambda * tensor4::outer(kI, kI) + 2.0 * mu * tensor4::sym_product(kI);
    const Tangent6 T = p.make()->tangent(kI);
    EXPECT_LT((T - expected).norm(), test::kRelativeRoundoff * expected.norm()) << p.make()->name();
  }
}

TEST(OgdenLaw, UniaxialStressMatchesClosedForm) {
  // Stretches (lambda, s, s), J = lambda s^2, λ̄1 = lambda J^-1/3, λ̄2 = λ̄3 = s J^-1/3. The principal
  // Kirchhoff stresses of the law are tau_a = sum_i 2 mu_i / alpha_i (λ̄a^alpha_i - ē_i / 3)
  // + K J (J - 1). Lateral faces free: tau_2 = 0, i.e.
  //   f(s) = sum_i 2 mu_i / (3 alpha_i) (λ̄2^alpha_i - λ̄1^alpha_i) + K J (J - 1) = 0,
  // and then P11 = tau_1 / lambda = (tau_1 - tau_2) / lambda
  //                = sum_i 2 mu_i / alpha_i (λ̄1^alpha_i - λ̄2^alpha_i) / lambda.
  // f is solved here by its own bisection, independent of the law's code.
  const OgdenParams p{{700.0, 300.0}, {1.5, -4.0}, 75000.0};  // Pa, K / mu = 75
  const auto law = p.make();
  for (double lambda : {0.7, 0.9, 1.2, 1.5, 2.0}) {
    auto bars = [&](double s) {
      const double J = lambda * s * s, j13 = std::cbrt(J);
      return std::array<double, 3>{lambda / j13, s / j13, J};
    };
    auto f = [&](double s) {
      const auto [l1, l2, J] = bars(s);
      double v = p.K * J * (J - 1.0);
      for (std::size_t i = 0; i < p.mu.size(); ++i)
        v += 2.0 * p.mu[i] / (3.0 * p.alpha[i]) * (std::pow(l2, p.alpha[i]) - std::pow(l1, p.alpha[i]));
      return v;
    };
    double lo = 0.2, hi = 2.0;
    for (int it = 0; it < 200; ++it) {
      const double mid = 0.5 * (lo + hi);
      (f(mid) > 0 ? hi : lo) = mid;
    }
    const double s = 0.5 * (lo + hi);
    const auto [l1, l2, J] = bars(s);
    double P = 0.0;
    for (std::size_t i = 0; i < p.mu.size(); ++i)
      P += 2.0 * p.mu[i] / p.alpha[i] * (std::pow(l1, p.alpha[i]) - std::pow(l2, p.alpha[i])) / lambda;
    const auto got = uniaxial(*law, lambda);
    EXPECT_NEAR(got[0], P, test::kRelativeRoundoff * std::abs(P)) << lambda;
    EXPECT_NEAR(got[1], s, test::kRelativeRoundoff) << lambda;
  }
}

TEST(OgdenLaw, UniaxialStressMatchesNeoHookeanReferenceValues) {
  // The uniaxial table's "NiftySim (J-1)^2, nu = 0.49" column (mu = 1000 Pa; docs/verification.md,
  // "Solver: analytic references"): Ogden N = 1, alpha = 2 is that energy. Values quoted to 6-7
  // significant digits.
  const double mu = 1000.0, K = 2.0 * mu * 1.49 / (3.0 * 0.02);
  const auto law = make_uncoupled_ogden({mu}, {2.0}, K);
  const struct {
    double lambda, P, s;
  } rows[] = {{1.2, 501.419, 0.914705}, {1.5, 1043.711, 0.820731}, {2.0, 1718.609, 0.715038}};
  for (const auto& r : rows) {
    const auto got = uniaxial(*law, r.lambda);
    EXPECT_NEAR(got[0], r.P, test::kQuotedSixDigitsRel * r.P) << r.lambda;
    EXPECT_NEAR(got[1], r.s, test::kQuotedSixDigitsRel * r.s) << r.lambda;
  }
}

TEST(OgdenLaw, RejectsInvalidTerms) {
  EXPECT_THROW(make_uncoupled_ogden({1.0, 2.0}, {2.0}, 1.0), InputError);  // size mismatch
  EXPECT_THROW(make_uncoupled_ogden({}, {}, 1.0), InputError);             // no term
  EXPECT_THROW(make_uncoupled_ogden({1, 1, 1, 1}, {1, 2, 3, 4}, 1.0), InputError);  // > 3 terms
  EXPECT_THROW(make_uncoupled_ogden({1.0, 1.0}, {2.0, 0.0}, 1.0), InputError);       // alpha = 0
  EXPECT_NO_THROW(make_uncoupled_ogden({1, 1, 1}, {1, 2, 3}, 1.0));
}
