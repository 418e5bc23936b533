// Built-in solver, element level (docs/solver.md, "Elements"): tet4/tet10 shape functions and
// quadrature, consistent body force, and the total-Lagrangian kernel (rigid motions, affine patch,
// tangent and force against finite differences, energy conjugacy, inversion flag).
#include "core/errors.h"
#include "core/unit_system.h"
#include "materials/hyperelastic_law.h"
#include "solver_check/element_kernel.h"
#include "solver_check/tet_shape.h"
#include "support/tolerances.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <Eigen/LU>

#include <cmath>
#include <functional>
#include <memory>
#include <vector>

using namespace tissuemesh;

namespace {

const ElementOrder kOrders[] = {ElementOrder::Linear, ElementOrder::Quadratic};
const char* order_name(ElementOrder o) { return o == ElementOrder::Linear ? "tet4" : "tet10"; }

// Points inside the reference tetrahedron (none on a symmetry plane).
std::vector<Eigen::Vector3d> sample_xi() {
  return {{0.1, 0.2, 0.3}, {0.6, 0.15, 0.05}, {0.05, 0.7, 0.1}, {0.2, 0.1, 0.65}, {0.31, 0.27, 0.19}};
}

// A distorted, positively oriented corner tetrahedron (unit size, volume ~0.22).
Eigen::Matrix<double, 4, 3> corners() {
  Eigen::Matrix<double, 4, 3> X;
  X << 0.1, -0.2, 0.05, 1.3, 0.1, -0.1, 0.2, 0.9, 0.15, 0.3, 0.25, 1.1;
  return X;
}

// Element nodes of `order` from the corners; tet10 midsides at the edge midpoints plus `bulge`
// (a curved, isoparametrically distorted tet10 when bulge != 0).
ElementNodes element(ElementOrder order, double bulge = 0.0) {
  const auto C = corners();
  ElementNodes X(tet_node_count(order), 3);
  for (int a = 0; a < X.rows(); ++a) {
    const Eigen::Vector3d xi = tet_node_xi(order, a);
    X.row(a) = (1 - xi.sum()) * C.row(0) + xi(0) * C.row(1) + xi(1) * C.row(2) + xi(2) * C.row(3);
    if (a >= 4) X.row(a) += bulge * Eigen::RowVector3d(std::sin(3.0 * a), std::cos(5.0 * a), std::sin(7.0 * a + 1));
  }
  return X;
}

double corner_volume() {
  const auto C = corners();
  const Eigen::Vector3d a = (C.row(1) - C.row(0)).transpose(), b = (C.row(2) - C.row(0)).transpose(),
                        c = (C.row(3) - C.row(0)).transpose();
  return a.dot(b.cross(c)) / 6.0;
}

// Homogeneous deformation u = (F - I) X + c at every node.
ElementNodes affine_u(const ElementNodes& X, const Eigen::Matrix3d& F, const Eigen::Vector3d& c) {
  ElementNodes u(X.rows(), 3);
  for (int a = 0; a < X.rows(); ++a) u.row(a) = ((F - Eigen::Matrix3d::Identity()) * X.row(a).transpose() + c).transpose();
  return u;
}

Eigen::Matrix3d sample_F() {
  Eigen::Matrix3d F;
  F << 1.15, 0.12, -0.05, 0.03, 0.92, 0.08, -0.04, 0.06, 1.01;
  return F;
}

// Non-affine displacement: the affine part plus quadratic terms of size ~0.05.
ElementNodes curved_u(const ElementNodes& X) {
  ElementNodes u = affine_u(X, sample_F(), Eigen::Vector3d(0.2, -0.1, 0.3));
  for (int a = 0; a < X.rows(); ++a) {
    const double x = X(a, 0), y = X(a, 1), z = X(a, 2);
    u.row(a) += 0.06 * Eigen::RowVector3d(y * y - x * z, x * y + z * z, -x * x + y * z);
  }
  return u;
}

std::vector<std::unique_ptr<HyperelasticLaw>> laws() {
  std::vector<std::unique_ptr<HyperelasticLaw>> v;
  v.push_back(make_compressible_neo_hookean(1.3, 4.1));
  v.push_back(make_uncoupled_mooney_rivlin(0.6, 0.0, 5.0));
  v.push_back(make_uncoupled_mooney_rivlin(0.4, 0.25, 3.0));
  v.push_back(make_uncoupled_ogden({0.7, 0.2}, {2.0, -2.0}, 5.0));
  return v;
}

ElementVector as_vector(const ElementNodes& u) {
  ElementVector v(3 * u.rows());
  for (int a = 0; a < u.rows(); ++a) v.segment<3>(3 * a) = u.row(a).transpose();
  return v;
}

ElementNodes perturbed(ElementNodes u, int dof, double h) {
  u(dof / 3, dof % 3) += h;
  return u;
}

double factorial(int n) { return n <= 1 ? 1.0 : n * factorial(n - 1); }

}  // namespace

TEST(TetShape, PartitionOfUnityAndKroneckerProperty) {
  for (ElementOrder o : kOrders) {
    const int n = tet_node_count(o);
    for (const auto& xi : sample_xi()) {
      EXPECT_NEAR(tet_shape_values(o, xi).sum(), 1.0, test::kRelativeRoundoff) << order_name(o);
      EXPECT_LT(tet_shape_derivatives(o, xi).colwise().sum().norm(), test::kRelativeRoundoff) << order_name(o);
    }
    // Midside nodes 4..9 sit on the edges (0,1) (1,2) (2,0) (0,3) (1,3) (2,3) of model.h.
    const int edges[6][2] = {{0, 1}, {1, 2}, {2, 0}, {0, 3}, {1, 3}, {2, 3}};
    for (int m = 0; o == ElementOrder::Quadratic && m < 6; ++m)
      EXPECT_LT((tet_node_xi(o, 4 + m) - 0.5 * (tet_node_xi(o, edges[m][0]) + tet_node_xi(o, edges[m][1]))).norm(),
                test::kRelativeRoundoff) << "midside " << 4 + m;
    for (int b = 0; b < n; ++b) {
      const ShapeValues N = tet_shape_values(o, tet_node_xi(o, b));
      for (int a = 0; a < n; ++a) EXPECT_NEAR(N(a), a == b ? 1.0 : 0.0, test::kRelativeRoundoff) << order_name(o) << a << b;
    }
  }
}

TEST(TetShape, DerivativesMatchFiniteDifferences) {
  // N is at most quadratic: the central difference is exact but for round-off ~1e-16/h = 1e-10.
  const double h = 1e-6;
  for (ElementOrder o : kOrders)
    for (const auto& xi : sample_xi()) {
      const ShapeGradients dN = tet_shape_derivatives(o, xi);
      for (int j = 0; j < 3; ++j) {
        const Eigen::Vector3d e = h * Eigen::Vector3d::Unit(j);
        const ShapeValues fd = (tet_shape_values(o, xi + e) - tet_shape_values(o, xi - e)) / (2 * h);
        EXPECT_LT((fd - dN.col(j)).cwiseAbs().maxCoeff(), test::kFiniteDifferenceRel * dN.cwiseAbs().maxCoeff())
            << order_name(o) << " d/dxi" << j;
      }
    }
}

TEST(TetShape, IsoparametricInterpolationReproducesCompletePolynomials) {
  // On a straight element the map is affine: tet4 reproduces linear fields, tet10 quadratic ones,
  // values and physical gradients, exactly.
  auto phi = [](ElementOrder o, const Eigen::Vector3d& X) {
    const double lin = 0.3 + 1.1 * X(0) - 0.7 * X(1) + 0.4 * X(2);
    return o == ElementOrder::Linear ? lin : lin + 0.9 * X(0) * X(1) - 0.5 * X(2) * X(2) + 0.2 * X(0) * X(0);
  };
  auto grad = [](ElementOrder o, const Eigen::Vector3d& X) {
    Eigen::Vector3d g(1.1, -0.7, 0.4);
    if (o == ElementOrder::Quadratic) g += Eigen::Vector3d(0.9 * X(1) + 0.4 * X(0), 0.9 * X(0), -X(2));
    return g;
  };
  for (ElementOrder o : kOrders) {
    const ElementNodes X = element(o);
    Eigen::VectorXd nodal(X.rows());
    for (int a = 0; a < X.rows(); ++a) nodal(a) = phi(o, X.row(a).transpose());
    for (const auto& xi : sample_xi()) {
      const ShapeValues N = tet_shape_values(o, xi);
      const ShapeGradients dN = tet_shape_derivatives(o, xi);
      const Eigen::Matrix3d Jref = X.transpose() * dN;
      const Eigen::Vector3d Xp = X.transpose() * N;
      const Eigen::Vector3d g = (dN * Jref.inverse()).transpose() * nodal;
      EXPECT_NEAR(N.dot(nodal), phi(o, Xp), test::kRelativeRoundoff) << order_name(o);
      EXPECT_LT((g - grad(o, Xp)).norm(), test::kRelativeRoundoff) << order_name(o);
    }
  }
}

TEST(TetQuadrature, IntegratesPolynomialsOfItsDegreeExactly) {
  // int r^i s^j t^k over the reference tet = i! j! k! / (i + j + k + 3)!.
  for (int degree : {1, 2}) {
    const QuadratureRule& rule = tet_quadrature(degree);
    bool next_degree_exact = true;
    for (int i = 0; i <= degree + 1; ++i)
      for (int j = 0; i + j <= degree + 1; ++j)
        for (int k = 0; i + j + k <= degree + 1; ++k) {
          double sum = 0.0;
          for (const auto& qp : rule) sum += qp.weight * std::pow(qp.xi(0), i) * std::pow(qp.xi(1), j) * std::pow(qp.xi(2), k);
          const double exact = factorial(i) * factorial(j) * factorial(k) / factorial(i + j + k + 3);
          if (i + j + k <= degree)
            EXPECT_NEAR(sum, exact, test::kRelativeRoundoff * exact) << degree << ": " << i << j << k;
          else if (std::abs(sum - exact) > test::kRelativeRoundoff * exact)
            next_degree_exact = false;
        }
    EXPECT_FALSE(next_degree_exact) << "degree " << degree << " rule is documented as not exact one degree up";
  }
  EXPECT_EQ(tet_stiffness_rule(ElementOrder::Linear).size(), 1u);
  EXPECT_EQ(tet_stiffness_rule(ElementOrder::Quadratic).size(), 4u);
  EXPECT_EQ(tet_load_rule(ElementOrder::Quadratic).size(), 4u);
  EXPECT_THROW(tet_quadrature(3), std::invalid_argument);
}

TEST(ElementBodyForce, SumsToTheWeightWithTheConsistentDistribution) {
  const double rho = 1.07;
  const Eigen::Vector3d g(0.3, -9.81, 1.2);
  const double V = corner_volume();
  ASSERT_GT(V, 0.0);
  for (ElementOrder o : kOrders) {
    const ElementNodes X = element(o);
    EXPECT_NEAR(element_reference_volume(o, X), V, test::kRelativeRoundoff * V);
    const ElementVector f = element_body_force(o, X, rho, g);
    Eigen::Vector3d total = Eigen::Vector3d::Zero();
    for (int a = 0; a < X.rows(); ++a) total += f.segment<3>(3 * a);
    EXPECT_LT((total - rho * V * g).norm(), test::kRelativeRoundoff * rho * V * g.norm()) << order_name(o);
    // tet4: 1/4 per node; tet10: -1/20 at the corners, 1/5 at the midsides.
    for (int a = 0; a < X.rows(); ++a) {
      const double share = o == ElementOrder::Linear ? 0.25 : (a < 4 ? -0.05 : 0.2);
      EXPECT_LT((f.segment<3>(3 * a) - share * rho * V * g).norm(), test::kRelativeRoundoff * rho * V * g.norm())
          << order_name(o) << " node " << a;
    }
  }
}

TEST(ElementBodyForce, WaterInMillimetreTonneSecondWeighsNewtons) {
  // 1 mm^3 of water (1000 kg/m^3) under 9.81 m/s^2 weighs 9.81e-6 N; in mm-t-s the kernel's
  // density x acceleration x mm^3 must come out in N.
  const auto units = UnitSystem::MillimetreTonneSecond;
  const ElementNodes X = element(ElementOrder::Quadratic);
  const double V = corner_volume();
  const ElementVector f = element_body_force(ElementOrder::Quadratic, X, density_from_kg_per_m3(units, 1000.0),
                                             Eigen::Vector3d(0, 0, acceleration_from_m_per_s2(units, -9.81)));
  double fz = 0.0;
  for (int a = 0; a < 10; ++a) fz += f(3 * a + 2);
  EXPECT_NEAR(fz / V, -9.81e-6, test::kRelativeRoundoff * 9.81e-6);
}

TEST(ElementKernel, RigidTranslationAndRotationGiveNoForce) {
  // C = R^T R = I up to round-off: force ~1e-16 of the force scale |K_0| x size; 1e-9 of it.
  const Eigen::Matrix3d R = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d(1, 2, 2).normalized()).toRotationMatrix();
  for (ElementOrder o : kOrders)
    for (const auto& law : laws()) {
      const ElementNodes X = element(o, 0.04);
      const double scale = element_response(o, X, ElementNodes::Zero(X.rows(), 3), *law).tangent.norm();
      for (const Eigen::Matrix3d& F : {Eigen::Matrix3d::Identity().eval(), R}) {
        const ElementResponse r = element_response(o, X, affine_u(X, F, Eigen::Vector3d(3.0, -2.0, 0.5)), *law);
        ASSERT_TRUE(r.ok()) << order_name(o) << " " << law->name();
        EXPECT_NEAR(r.energy, 0.0, test::kRelativeRoundoff * scale) << order_name(o) << " " << law->name();
        EXPECT_LT(r.force.norm(), test::kRelativeRoundoff * scale) << order_name(o) << " " << law->name();
        EXPECT_NEAR(r.min_J, 1.0, test::kRelativeRoundoff);
      }
    }
}

TEST(ElementKernel, AffinePatchForceEqualsBoundaryTraction) {
  // Homogeneous F: P = F S(F^T F) is constant, div P = 0, so f_a = int P grad N_a dV equals the
  // boundary traction integral sum_faces (int_face N_a dA) P n_face, with S taken from the law
  // directly. int_face N_a dA: A/3 per corner (tri3); 0 per corner and A/3 per midside (tri6).
  for (ElementOrder o : kOrders)
    for (const auto& law : laws()) {
      const ElementNodes X = element(o);
      const Eigen::Matrix3d F = sample_F();
      const ElementResponse r = element_response(o, X, affine_u(X, F, Eigen::Vector3d(0.1, 0.2, -0.3)), *law,
                                                 ElementOutput::EnergyAndForce);
      ASSERT_TRUE(r.ok());
      const Eigen::Matrix3d P = F * law->pk2(F.transpose() * F);
      ElementVector traction = ElementVector::Zero(3 * X.rows());
      for (int face = 0; face < 4; ++face) {
        const auto& c = face_corners(face);
        const Eigen::Vector3d area = 0.5 * (X.row(c[1]) - X.row(c[0])).transpose().cross((X.row(c[2]) - X.row(c[0])).transpose());
        const Eigen::Vector3d t = P * area;  // outward: face_corners is outward oriented
        for (int k = 0; k < 3; ++k) {
          const int node = o == ElementOrder::Linear ? c[k] : face_midsides(face)[k];
          traction.segment<3>(3 * node) += t / 3.0;
        }
      }
      EXPECT_LT((r.force - traction).norm(), test::kRelativeRoundoff * traction.norm()) << order_name(o) << " " << law->name();
      EXPECT_NEAR(r.energy, law->energy(F.transpose() * F) * corner_volume(), test::kRelativeRoundoff * std::abs(r.energy));
    }
}

TEST(ElementKernel, TangentIsTheFiniteDifferenceOfTheForce) {
  // Central differences with h = 1e-6 on a unit-size element with unit moduli (the setting
  // kFiniteDifferenceRel is justified for), relative to the tangent's largest entry.
  const double h = 1e-6;
  for (ElementOrder o : kOrders)
    for (const auto& law : laws()) {
      const ElementNodes X = element(o, o == ElementOrder::Quadratic ? 0.04 : 0.0);
      const ElementNodes u = curved_u(X);
      const ElementResponse r = element_response(o, X, u, *law);
      ASSERT_TRUE(r.ok()) << order_name(o) << " " << law->name();
      const double scale = r.tangent.cwiseAbs().maxCoeff();
      EXPECT_LT((r.tangent - r.tangent.transpose()).cwiseAbs().maxCoeff(), test::kRelativeRoundoff * scale);
      for (int d = 0; d < 3 * X.rows(); ++d) {
        const ElementVector fp = element_response(o, X, perturbed(u, d, h), *law, ElementOutput::EnergyAndForce).force;
        const ElementVector fm = element_response(o, X, perturbed(u, d, -h), *law, ElementOutput::EnergyAndForce).force;
        const ElementVector fd = (fp - fm) / (2 * h);
        EXPECT_LT((fd - r.tangent.col(d)).cwiseAbs().maxCoeff(), test::kFiniteDifferenceRel * scale)
            << order_name(o) << " " << law->name() << " dof " << d;
      }
    }
}

TEST(ElementKernel, ForceIsTheFiniteDifferenceGradientOfTheEnergy) {
  const double h = 1e-6;  // as above, relative to the largest force component
  for (ElementOrder o : kOrders)
    for (const auto& law : laws()) {
      const ElementNodes X = element(o, o == ElementOrder::Quadratic ? 0.04 : 0.0);
      const ElementNodes u = curved_u(X);
      const ElementResponse r = element_response(o, X, u, *law, ElementOutput::EnergyAndForce);
      ASSERT_TRUE(r.ok());
      const double scale = r.force.cwiseAbs().maxCoeff();
      for (int d = 0; d < 3 * X.rows(); ++d) {
        const double fd = (element_response(o, X, perturbed(u, d, h), *law, ElementOutput::Energy).energy -
                           element_response(o, X, perturbed(u, d, -h), *law, ElementOutput::Energy).energy) / (2 * h);
        EXPECT_NEAR(r.force(d), fd, test::kFiniteDifferenceRel * scale) << order_name(o) << " " << law->name() << " dof " << d;
      }
    }
}

TEST(ElementKernel, EnergyConjugacyOnADistortedTet10) {
  // Curved (bulged midsides), non-affine, finite path: Pi(u1) - Pi(u0) = int_0^1 f(u(s)) . du ds
  // with u(s) = u0 + s (u1 - u0), by composite 2-point Gauss on 100 panels (kPathIntegralRel).
  const ElementOrder o = ElementOrder::Quadratic;
  const ElementNodes X = element(o, 0.08);
  const ElementNodes u0 = ElementNodes::Zero(10, 3);
  const ElementNodes u1 = curved_u(X);
  const ElementVector du = as_vector(u1 - u0);
  for (const auto& law : laws()) {
    const int panels = 100;
    const double g = 0.5 / std::sqrt(3.0);
    double work = 0.0;
    for (int p = 0; p < panels; ++p)
      for (double s : {(p + 0.5 - g) / panels, (p + 0.5 + g) / panels}) {
        const ElementResponse r = element_response(o, X, u0 + s * (u1 - u0), *law, ElementOutput::EnergyAndForce);
        ASSERT_TRUE(r.ok()) << law->name() << " s = " << s;
        work += 0.5 / panels * r.force.dot(du);
      }
    const double dPi = element_response(o, X, u1, *law, ElementOutput::Energy).energy -
                       element_response(o, X, u0, *law, ElementOutput::Energy).energy;
    ASSERT_GT(dPi, 0.0);
    EXPECT_NEAR(work, dPi, test::kPathIntegralRel * dPi) << law->name();
  }
}

TEST(ElementKernel, InversionIsFlaggedWithoutNaN) {
  const auto law = make_compressible_neo_hookean(1.3, 4.1);
  for (ElementOrder o : kOrders) {
    const ElementNodes X = element(o);
    // Push every node through the plane z = const (J < 0 everywhere): mirror z.
    const ElementResponse r = element_response(o, X, affine_u(X, Eigen::Vector3d(1, 1, -1).asDiagonal(), Eigen::Vector3d::Zero()), *law);
    EXPECT_EQ(r.status, ElementStatus::Inverted) << order_name(o);
    EXPECT_EQ(r.failed_point, 0);
    EXPECT_LE(r.min_J, 0.0);
    EXPECT_TRUE(r.force.allFinite() && r.tangent.allFinite() && std::isfinite(r.energy));
    EXPECT_EQ(r.force.norm(), 0.0);
    EXPECT_EQ(r.tangent.norm(), 0.0);
    // Flat (J = 0): still flagged, not NaN.
    const ElementResponse flat = element_response(o, X, affine_u(X, Eigen::Vector3d(1, 1, 0).asDiagonal(), Eigen::Vector3d::Zero()), *law);
    EXPECT_EQ(flat.status, ElementStatus::Inverted) << order_name(o);
    // A mirrored reference element is an invalid mesh: its own status, and the load refuses it.
    ElementNodes Xm = X;
    Xm.col(2) *= -1.0;
    EXPECT_EQ(element_response(o, Xm, ElementNodes::Zero(X.rows(), 3), *law).status, ElementStatus::InvertedReference);
    EXPECT_THROW(element_body_force(o, Xm, 1.0, Eigen::Vector3d(0, 0, -1)), SolverError);
    EXPECT_THROW(element_response(o, X.topRows(3), ElementNodes::Zero(3, 3), *law), std::invalid_argument);
  }
}
