// Per-element results of a solved state (solver_check/cell_fields.h) against closed forms: a
// homogeneous deformation gives the law's analytic Cauchy stress and J = det F in every cell (tet4
// and tet10, model in mm or in metres), no displacement and a rigid rotation give no stress.
#include "solver_check/cell_fields.h"

#include "core/errors.h"
#include "support/model_fixture.h"
#include "support/tolerances.h"

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>
#include <tuple>

namespace tissuemesh {
namespace {

Model block(ElementOrder order, UnitSystem units) {
  test::BlockModelOptions options;
  options.order = order;
  options.units = units;
  return test::block_model(options);
}

/// u = (F - I) X at every node, in the model's length unit (nodes are in mm).
std::vector<Eigen::Vector3d> homogeneous(const Model& model, const Eigen::Matrix3d& F) {
  std::vector<Eigen::Vector3d> u;
  for (const Eigen::Vector3d& X : model.nodes) u.push_back(length_from_mm(model.units, 1.0) * (F - Eigen::Matrix3d::Identity()) * X);
  return u;
}

/// Cauchy stress of the uncoupled Mooney-Rivlin law W = C10 (I1bar - 3) + C01 (I2bar - 3) +
/// K/2 (J - 1)^2 (neo-Hookean: C01 = 0), Pa (Holzapfel, Nonlinear Solid Mechanics, 6.6):
///   sigma = 2/J dev[(C10 + C01 I1bar) Bbar - C01 Bbar^2] + K (J - 1) I,  Bbar = J^(-2/3) F F^T.
Eigen::Matrix3d mooney_rivlin_cauchy(const MaterialSpec& m, const Eigen::Matrix3d& F) {
  const double J = F.determinant();
  const double C10 = m.law == MaterialLaw::NeoHookean ? m.mu_Pa / 2.0 : m.C10_Pa;
  const double C01 = m.law == MaterialLaw::NeoHookean ? 0.0 : m.C01_Pa;
  const Eigen::Matrix3d Bbar = std::pow(J, -2.0 / 3.0) * F * F.transpose();
  const Eigen::Matrix3d tau = 2.0 * ((C10 + C01 * Bbar.trace()) * Bbar - C01 * Bbar * Bbar);
  const Eigen::Matrix3d I = Eigen::Matrix3d::Identity();
  return (tau - tau.trace() / 3.0 * I) / J + m.K_Pa * (J - 1.0) * I;
}

class HomogeneousDeformation : public ::testing::TestWithParam<std::tuple<ElementOrder, UnitSystem>> {};

/// Every cell of `model` under u = (F - I) X has the analytic Cauchy stress, J and von Mises.
void expect_analytic_fields(const Model& model) {
  Eigen::Matrix3d F;
  F << 1.05, 0.02, 0.01,  //
      0.03, 0.97, 0.04,   //
      -0.02, 0.01, 1.02;
  const CellFields f = cell_fields(model, homogeneous(model, F));
  ASSERT_EQ(f.cauchy_stress_Pa.size(), model.elements.size());
  ASSERT_EQ(f.J.size(), model.elements.size());
  ASSERT_EQ(f.von_mises_Pa.size(), model.elements.size());
  for (std::size_t e = 0; e < model.elements.size(); ++e) {
    const MaterialSpec& m = model.materials[model.tissue_ids[e] - 1];
    ASSERT_TRUE(m.law == MaterialLaw::NeoHookean || m.law == MaterialLaw::MooneyRivlin);
    const Eigen::Matrix3d s = mooney_rivlin_cauchy(m, F);
    const StressVoigt expected = (StressVoigt() << s(0, 0), s(1, 1), s(2, 2), s(0, 1), s(1, 2), s(0, 2)).finished();
    const double tol = test::kStressRoundoffRel * m.K_Pa;
    for (int k = 0; k < 6; ++k) ASSERT_NEAR(f.cauchy_stress_Pa[e][k], expected[k], tol) << "element " << e << " " << k;
    ASSERT_NEAR(f.J[e], F.determinant(), test::kStressRoundoffRel) << e;
    ASSERT_NEAR(f.von_mises_Pa[e], von_mises(expected), tol) << e;
  }
}

TEST_P(HomogeneousDeformation, GivesTheAnalyticCauchyStressAndJInEveryCell) {
  const auto [order, units] = GetParam();
  expect_analytic_fields(block(order, units));
}

TEST(CellFields, NodalPressureTet4GivesTheAnalyticStressUnderHomogeneousDeformation) {
  // Every patch then has the element's J: shear part + mean nodal pressure = the full law's stress.
  for (UnitSystem units : {UnitSystem::MillimetreTonneSecond, UnitSystem::SI}) {
    Model model = block(ElementOrder::Linear, units);
    model.analysis.tet4_pressure = Tet4Pressure::Nodal;
    expect_analytic_fields(model);
  }
}

TEST_P(HomogeneousDeformation, NoDisplacementAndRigidRotationGiveNoStress) {
  const auto [order, units] = GetParam();
  const Model model = block(order, units);
  const CellFields still = cell_fields(model, std::vector<Eigen::Vector3d>(model.nodes.size(), Eigen::Vector3d::Zero()));
  for (std::size_t e = 0; e < model.elements.size(); ++e) {
    const double tol = test::kStressRoundoffRel * model.materials[model.tissue_ids[e] - 1].K_Pa;
    for (int k = 0; k < 6; ++k) ASSERT_NEAR(still.cauchy_stress_Pa[e][k], 0.0, tol) << e;
    ASSERT_EQ(still.J[e], 1.0) << e;
  }
  // A finite rotation (40 degrees): the total-Lagrangian stress is objective, so zero.
  const Eigen::Matrix3d R = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  const CellFields turned = cell_fields(model, homogeneous(model, R));
  for (std::size_t e = 0; e < model.elements.size(); ++e) {
    const double tol = test::kStressRoundoffRel * model.materials[model.tissue_ids[e] - 1].K_Pa;
    for (int k = 0; k < 6; ++k) ASSERT_NEAR(turned.cauchy_stress_Pa[e][k], 0.0, tol) << e;
    ASSERT_NEAR(turned.von_mises_Pa[e], 0.0, tol) << e;
    ASSERT_NEAR(turned.J[e], 1.0, test::kStressRoundoffRel) << e;
  }
}

INSTANTIATE_TEST_SUITE_P(CellFields, HomogeneousDeformation,
                         ::testing::Combine(::testing::Values(ElementOrder::Linear, ElementOrder::Quadratic),
                                            ::testing::Values(UnitSystem::MillimetreTonneSecond, UnitSystem::SI)),
                         [](const auto& info) {
                           return test::order_units_name(std::get<0>(info.param), std::get<1>(info.param));
                         });

TEST(CellFields, VonMisesOfUniaxialAndShearStress) {
  EXPECT_DOUBLE_EQ(von_mises((StressVoigt() << 250, 0, 0, 0, 0, 0).finished()), 250.0);
  EXPECT_DOUBLE_EQ(von_mises((StressVoigt() << 0, 0, 0, 0, 10, 0).finished()), std::sqrt(3.0) * 10.0);
  EXPECT_DOUBLE_EQ(von_mises((StressVoigt() << -7, -7, -7, 0, 0, 0).finished()), 0.0);  // pressure
}

TEST(CellFields, InvertedStateAndWrongSizeAreRefused) {
  const Model model = block(ElementOrder::Linear, UnitSystem::MillimetreTonneSecond);
  try {
    cell_fields(model, homogeneous(model, -Eigen::Matrix3d::Identity()));  // J = -1
    FAIL() << "no error";
  } catch (const SolverError& e) {
    EXPECT_NE(std::string(e.what()).find("element 0 (tissue 'fat')"), std::string::npos) << e.what();
  }
  EXPECT_THROW(cell_fields(model, std::vector<Eigen::Vector3d>(3)), std::invalid_argument);
}

}  // namespace
}  // namespace tissuemesh
