// The average-nodal-pressure tet4 (solver_check/nodal_pressure.h) in the reduced assembly: force
// and tangent against finite differences of the energy (sliding and fixed nodes included), the
// affine patch (identical to the standard tet4 under a homogeneous deformation), and the locking
// it cures: the nearly incompressible block sags like tet10, not like the standard tet4.
#include "solver/block_assembly.h"
#include "solver_check/static_solver.h"
#include "support/model_fixture.h"
#include "support/tolerances.h"

#include <gtest/gtest.h>

#include <Eigen/SparseCore>

#include <cmath>
#include <iostream>
#include <memory>
#include <vector>

namespace tissuemesh {
namespace {

TEST(NodalPressure, ForceAndTangentAreTheDerivativesOfTheEnergy) {
  test::BlockAssembly b;
  const Eigen::VectorXd q = b.smooth_q(0.3);
  const ReducedAssembly::Result r = b.with_nodal->assemble(b.dofs->expand(q, 0.0), true);
  ASSERT_TRUE(r.ok) << r.note;
  const Eigen::VectorXd f = b.dofs->reduce(r.f_int);
  const Eigen::SparseMatrix<double> K = b.with_nodal->tangent();
  // Central differences along three directions; the energy is smooth, so the scheme's O(h^2)
  // error and round-off stay below kFiniteDifferenceRel of the derivative's own scale.
  const double h = 1e-6;
  for (int k = 0; k < 3; ++k) {
    const Eigen::VectorXd w = b.smooth_q(1.0 + k).cwiseProduct(Eigen::VectorXd::LinSpaced(q.size(), 0.5, -0.7 + k));
    auto at = [&](double t) { return b.with_nodal->assemble(b.dofs->expand(q + t * w, 0.0), false); };
    const ReducedAssembly::Result plus = at(h), minus = at(-h);
    ASSERT_TRUE(plus.ok && minus.ok);
    const double dE = (plus.energy - minus.energy) / (2 * h);
    EXPECT_NEAR(f.dot(w), dE, test::kFiniteDifferenceRel * f.norm() * w.norm()) << "direction " << k;
    const Eigen::VectorXd df = b.dofs->reduce(plus.f_int - minus.f_int) / (2 * h);
    const Eigen::VectorXd Kw = K.selfadjointView<Eigen::Lower>() * w;
    EXPECT_LT((Kw - df).norm(), test::kFiniteDifferenceRel * df.norm()) << "direction " << k;
  }
}

TEST(NodalPressure, HomogeneousDeformationGivesTheStandardTet4ForceAndEnergy) {
  // Affine u = (F - I) X: every element has the same J, so every patch does too and the nodal
  // integration of U(J) is exact; force and energy equal the standard tet4's to round-off.
  test::BlockAssembly b;
  Eigen::Matrix3d A;
  A << 0.02, 0.01, -0.015, 0.005, -0.03, 0.01, 0.012, 0.0, 0.025;
  Eigen::VectorXd u(3 * b.model.nodes.size());
  for (std::size_t v = 0; v < b.model.nodes.size(); ++v) u.segment<3>(3 * v) = A * b.model.nodes[v];
  const ReducedAssembly::Result s = b.standard->assemble(u, false), n = b.with_nodal->assemble(u, false);
  ASSERT_TRUE(s.ok && n.ok);
  EXPECT_NEAR(n.energy, s.energy, test::kRelativeRoundoff * s.energy);
  EXPECT_LT((n.f_int - s.f_int).norm(), test::kRelativeRoundoff * s.f_int.norm());
}

TEST(NodalPressure, InvertedElementIsReportedNotAssembled) {
  test::BlockAssembly b;
  Eigen::VectorXd u = Eigen::VectorXd::Zero(3 * b.model.nodes.size());
  const int e = 700, node = b.model.elements[e][0];
  // Push corner 0 through the opposite face: element 700 (and maybe others) inverts.
  const Eigen::Vector3d c = (b.model.nodes[b.model.elements[e][1]] + b.model.nodes[b.model.elements[e][2]] +
                             b.model.nodes[b.model.elements[e][3]]) / 3.0;
  u.segment<3>(3 * node) = 2.5 * (c - b.model.nodes[node]);
  const ReducedAssembly::Result r = b.with_nodal->assemble(u, true);
  EXPECT_FALSE(r.ok);
  EXPECT_NE(r.note.find("inverted element"), std::string::npos) << r.note;
}

double max_sag(const SolveResult& r) {
  double m = 0.0;
  for (const Eigen::Vector3d& v : r.displacements) m = std::max(m, v.norm());
  return m;
}

TEST(NodalPressure, NearlyIncompressibleBlockSagsLikeTet10) {
  // The block's tissues have nu ~ 0.4985-0.4998. The standard tet4 locks (one volume constraint
  // per element, ~5 per node); the nodal one has one per node and patch.
  test::BlockModelOptions options;
  Model tet4 = test::block_model(options);
  Model nodal = tet4;
  nodal.analysis.tet4_pressure = Tet4Pressure::Nodal;
  options.order = ElementOrder::Quadratic;
  const Model tet10 = test::block_model(options);
  const SolveResult a = solve_static(tet4), b = solve_static(nodal), c = solve_static(tet10);
  ASSERT_TRUE(a.converged && b.converged && c.converged) << a.message << b.message << c.message;
  EXPECT_EQ(b.formulation, "tet4, average nodal pressure");
  const double s4 = max_sag(a), sn = max_sag(b), s10 = max_sag(c);
  std::cout << "[ locking  ] max |u|: tet4 " << s4 << " mm, tet4 nodal pressure " << sn << " mm, tet10 " << s10
            << " mm\n";
  const double weight = b.total_load.norm();
  EXPECT_LT((b.total_reaction + b.total_load).norm(), test::kSolverDefaultEquilibriumRel * weight);
  EXPECT_LT(std::abs(sn - s10), test::kLockingFreeRel * s10);
  EXPECT_GT(std::abs(s4 - s10), 2.0 * test::kLockingFreeRel * s10);  // the standard tet4 really locks here
}

}  // namespace
}  // namespace tissuemesh
