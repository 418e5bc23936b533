// Hyperelastic laws: stress and tangent against finite differences of the energy, zero stress in
// the reference state, and homogeneous uniaxial stress against tabulated reference values
// (docs/verification.md, "Solver: analytic references").
#include "materials/elastic_constants.h"
#include "materials/hyperelastic_law.h"
#include "materials/tensor4.h"
#include "materials/volumetric_split.h"
#include "support/finite_difference.h"
#include "support/tolerances.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <functional>

using namespace tissuemesh;

using test::bump;

namespace {

// A deformation with stretch, shear and volume change (J ~ 1.07).
Eigen::Matrix3d sample_C() {
  Eigen::Matrix3d F;
  F << 1.15, 0.12, -0.05, 0.03, 0.92, 0.08, -0.04, 0.06, 1.01;
  return F.transpose() * F;
}

std::vector<std::unique_ptr<HyperelasticLaw>> laws() {
  std::vector<std::unique_ptr<HyperelasticLaw>> v;
  v.push_back(make_compressible_neo_hookean(1.3, 4.1));
  v.push_back(make_uncoupled_mooney_rivlin(0.6, 0.0, 5.0));
  v.push_back(make_uncoupled_mooney_rivlin(0.4, 0.25, 3.0));
  return v;
}


// Uniaxial stress: stretch lambda along x, lateral stretch s found by bisection so that S22 = 0;
// returns {P11 = lambda S11, s, J}.
std::array<double, 3> uniaxial(const HyperelasticLaw& law, double lambda) {
  double lo = 0.3, hi = 1.2;
  auto s22 = [&](double s) { return law.pk2(Eigen::Vector3d(lambda * lambda, s * s, s * s).asDiagonal())(1, 1); };
  for (int it = 0; it < 200; ++it) {
    const double mid = 0.5 * (lo + hi);
    (s22(mid) > 0 ? hi : lo) = mid;
  }
  const double s = 0.5 * (lo + hi);
  const Eigen::Matrix3d S = law.pk2(Eigen::Vector3d(lambda * lambda, s * s, s * s).asDiagonal());
  return {lambda * S(0, 0), s, lambda * s * s};
}

}  // namespace

TEST(HyperelasticLaws, StressIsTwiceTheEnergyGradient) {
  // Central differences: error ~ h^2 W''' ~ 1e-12 for h = 1e-6 at unit moduli; 1e-7 relative to
  // the stress scale leaves room for round-off (~1e-16 / h).
  const Eigen::Matrix3d C = sample_C();
  const double h = 1e-6;
  for (const auto& law : laws()) {
    const Eigen::Matrix3d S = law->pk2(C);
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) {
        const double fd = 2.0 * (law->energy(bump(C, i, j, h)) - law->energy(bump(C, i, j, -h))) / (2 * h);
        EXPECT_NEAR(S(i, j), fd, test::kFiniteDifferenceRel * S.norm()) << law->name() << " " << i << j;
      }
  }
}

TEST(HyperelasticLaws, TangentIsTwiceTheStressGradient) {
  const Eigen::Matrix3d C = sample_C();
  const double h = 1e-6;
  for (const auto& law : laws()) {
    const Tangent6 T = law->tangent(C);
    EXPECT_LT((T - T.transpose()).norm(), test::kRelativeRoundoff * T.norm()) << law->name();  // major symmetry
    for (int b = 0; b < 6; ++b) {
      const int k = tensor4::kVoigt[b][0], l = tensor4::kVoigt[b][1];
      const Eigen::Matrix3d dS = (law->pk2(bump(C, k, l, h)) - law->pk2(bump(C, k, l, -h))) / (2 * h);
      for (int a = 0; a < 6; ++a) {
        const double fd = 2.0 * dS(tensor4::kVoigt[a][0], tensor4::kVoigt[a][1]);
        EXPECT_NEAR(T(a, b), fd, test::kFiniteDifferenceRel * T.norm()) << law->name() << " " << a << b;
      }
    }
  }
}

TEST(HyperelasticLaws, VolumetricPartIsAFunctionOfJWithConsistentDerivatives) {
  // U' and U'' against central differences (same step and tolerance as above).
  const double h = 1e-6;
  for (const auto& law : laws()) {
    for (const double J : {0.8, 1.0, 1.07}) {
      const HyperelasticLaw::Volumetric v = law->volumetric(J);
      const double dU = (law->volumetric(J + h).U - law->volumetric(J - h).U) / (2 * h);
      const double d2U = (law->volumetric(J + h).dU - law->volumetric(J - h).dU) / (2 * h);
      EXPECT_NEAR(v.dU, dU, test::kFiniteDifferenceRel * std::max(1.0, std::abs(v.dU))) << law->name() << " " << J;
      EXPECT_NEAR(v.d2U, d2U, test::kFiniteDifferenceRel * std::abs(v.d2U)) << law->name() << " " << J;
    }
  }
  // The split itself: what is left, W - U(J), is the shear part of each law's formula.
  const Eigen::Matrix3d C = sample_C();
  const double J = std::sqrt(C.determinant());
  auto nh = make_compressible_neo_hookean(1.3, 4.1);
  EXPECT_NEAR(nh->energy(C) - nh->volumetric(J).U, 0.5 * 1.3 * (C.trace() - 3.0) - 1.3 * std::log(J),
              test::kRelativeRoundoff);
  // Uncoupled laws: a pure dilation C = J^(2/3) I has I1bar = 3, I2bar = 3, so W = U exactly.
  for (const auto& law : laws()) {
    if (law->name().rfind("uncoupled", 0) != 0) continue;
    const Eigen::Matrix3d dilation = std::pow(J, 2.0 / 3.0) * Eigen::Matrix3d::Identity();
    EXPECT_NEAR(law->energy(dilation), law->volumetric(J).U, test::kRelativeRoundoff) << law->name();
  }
}

TEST(HyperelasticLaws, ReferenceAndRigidRotationAreStressFree) {
  // C = R^T R = I for any rotation R: no energy, no stress.
  const Eigen::Matrix3d R = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d(1, 2, 2).normalized()).toRotationMatrix();
  const Eigen::Matrix3d C = R.transpose() * R;
  for (const auto& law : laws()) {
    EXPECT_NEAR(law->energy(C), 0.0, test::kRelativeRoundoff) << law->name();
    EXPECT_LT(law->pk2(C).norm(), test::kRelativeRoundoff) << law->name();
  }
}

TEST(HyperelasticLaws, UniaxialStressMatchesReferenceValues) {
  // The uniaxial table (docs/verification.md, "Solver: analytic references"), mu = 1000 Pa,
  // nu = 0.49: P11 and lateral stretch, given to 3 decimals (6-7 significant digits) there, so
  // 1e-3 Pa and 1e-6 are the comparison resolution.
  const auto e = ElasticConstants::from_shear_bulk(1000.0, 2 * 1000.0 * 1.49 / (3 * 0.02));
  const auto febio = make_compressible_neo_hookean(e.shear_modulus(), e.lame_lambda());
  const auto abaqus = make_uncoupled_mooney_rivlin(e.neo_hooke_C10(), 0.0, e.bulk_modulus());
  const struct {
    double lambda, p_ln, s_ln, p_j1, s_j1;
  } rows[] = {{1.2, 503.229, 0.914399, 501.419, 0.914705},
              {1.5, 1052.563, 0.819241, 1043.711, 0.820731},
              {2.0, 1747.462, 0.710687, 1718.609, 0.715038}};
  for (const auto& r : rows) {
    const auto a = uniaxial(*febio, r.lambda);
    EXPECT_NEAR(a[0], r.p_ln, 1e-3) << r.lambda;
    EXPECT_NEAR(a[1], r.s_ln, 1e-6) << r.lambda;
    const auto b = uniaxial(*abaqus, r.lambda);
    EXPECT_NEAR(b[0], r.p_j1, 1e-3) << r.lambda;
    EXPECT_NEAR(b[1], r.s_j1, 1e-6) << r.lambda;
  }
}

TEST(HyperelasticLaws, EvaluateGivesWhatTheThreeCallsGive) {
  // evaluate() (the element kernel's one call per quadrature point) shares the invariants of C
  // between W, S and CC but computes each with the same expressions in the same order as
  // energy(), pk2() and tangent(), so the values are equal bit for bit (the build enables no
  // floating-point contraction that could differ between the two routes). Every law, its shear
  // part (the nodal-pressure tet4's), and the calls without S or CC.
  std::vector<std::unique_ptr<HyperelasticLaw>> all = laws();
  all.push_back(make_uncoupled_ogden({0.7, 0.3}, {1.5, -4.0}, 10.0));
  std::vector<std::unique_ptr<HyperelasticLaw>> shear;
  for (const auto& law : all) shear.push_back(make_shear_part(*law));
  for (auto& s : shear) all.push_back(std::move(s));
  const Eigen::Matrix3d C = sample_C();
  for (const auto& law : all) {
    SCOPED_TRACE(law->name());
    Eigen::Matrix3d S;
    Tangent6 CC;
    EXPECT_EQ(law->evaluate(C, &S, &CC), law->energy(C));
    EXPECT_TRUE((S.array() == law->pk2(C).array()).all()) << S << "\nvs\n" << law->pk2(C);
    EXPECT_TRUE((CC.array() == law->tangent(C).array()).all());
    Eigen::Matrix3d S_only;
    EXPECT_EQ(law->evaluate(C, &S_only, nullptr), law->energy(C));
    EXPECT_TRUE((S_only.array() == S.array()).all());
    EXPECT_EQ(law->evaluate(C, nullptr, nullptr), law->energy(C));
  }
}
