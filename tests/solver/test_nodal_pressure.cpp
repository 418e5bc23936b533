// The average-nodal-pressure tet4 (solver_check/nodal_pressure.h) in the reduced assembly: force
// and tangent against finite differences of the energy (sliding and fixed nodes included), the
// affine patch (identical to the standard tet4 under a homogeneous deformation), and the locking
// it cures: the nearly incompressible block sags like tet10, not like the standard tet4.
#include "materials/make_law.h"
#include "materials/volumetric_split.h"
#include "solver_check/dof_map.h"
#include "solver_check/nodal_pressure.h"
#include "solver_check/reduced_assembly.h"
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

/// The block model (three tissues, fixed posterior face, sliding top with tilted normals) and both
/// assemblies of it.
struct Block {
  Model model;
  std::vector<std::unique_ptr<HyperelasticLaw>> laws, shear;
  std::vector<const HyperelasticLaw*> full, rest;
  std::vector<int> tissue;
  std::vector<ElementGeometry> geometry;
  std::unique_ptr<DofMap> dofs;
  std::unique_ptr<NodalPressure> nodal;
  std::unique_ptr<ReducedAssembly> standard, with_nodal;

  Block() {
    test::BlockModelOptions options;
    options.sliding_top = true;
    model = test::block_model(options);  // mm-t-s: laws in MPa, lengths in mm
    // Tilt the sliding normals, so that the top nodes' bases are not coordinate axes.
    for (NodeSet& set : model.node_sets)
      for (Eigen::Vector3d& n : set.normals) n = Eigen::Vector3d(0.3, -0.2, 1.0).normalized();
    for (const MaterialSpec& spec : model.materials) {
      laws.push_back(make_law(spec, model.units));
      shear.push_back(make_shear_part(*laws.back()));
    }
    geometry.resize(model.elements.size());
    for (std::size_t e = 0; e < model.elements.size(); ++e) {
      ElementNodes X(4, 3);
      for (int a = 0; a < 4; ++a) X.row(a) = model.nodes[model.elements[e][a]].transpose();
      EXPECT_EQ(element_geometry(ElementOrder::Linear, X, geometry[e]), ElementStatus::Ok);
      tissue.push_back(model.tissue_ids[e] - 1);
      full.push_back(laws[tissue.back()].get());
      rest.push_back(shear[tissue.back()].get());
    }
    dofs = std::make_unique<DofMap>(model, std::vector<PrescribedDisplacement>{});
    nodal = std::make_unique<NodalPressure>(model.elements, geometry, tissue, full);
    standard = std::make_unique<ReducedAssembly>(ElementOrder::Linear, model.elements, geometry, full, *dofs, 1);
    with_nodal =
        std::make_unique<ReducedAssembly>(ElementOrder::Linear, model.elements, geometry, rest, *dofs, 2, nodal.get());
  }

  /// A smooth displacement (mm) with shear and a few percent of volume change, on the free dofs.
  Eigen::VectorXd smooth_q(double amplitude) const {
    Eigen::VectorXd u(3 * model.nodes.size());
    for (std::size_t v = 0; v < model.nodes.size(); ++v) {
      const Eigen::Vector3d& X = model.nodes[v];
      u.segment<3>(3 * v) << std::sin(0.3 * X.x() + 0.2 * X.z()), std::cos(0.25 * X.y() - 0.1 * X.x()),
          std::sin(0.2 * X.z() + 0.3 * X.y());
    }
    return amplitude * dofs->reduce(u);
  }
};

TEST(NodalPressure, ForceAndTangentAreTheDerivativesOfTheEnergy) {
  Block b;
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
  Block b;
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
  Block b;
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
