#include "solver_check/element_kernel.h"

#include "core/errors.h"
#include "solver_check/tet_shape.h"

#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace tissuemesh {

namespace {

using BMatrix = Eigen::Matrix<double, 6, Eigen::Dynamic, 0, 6, 30>;

void check_rows(ElementOrder order, const ElementNodes& M, const char* what) {
  if (M.rows() != tet_node_count(order))
    throw std::invalid_argument(std::string("element kernel: ") + what + " has " + std::to_string(M.rows()) +
                                " rows, expected " + std::to_string(tet_node_count(order)));
}

// Jacobian dX/dxi (J_ij = dX_i/dxi_j) of the isoparametric map at a point with derivatives dNdxi.
Eigen::Matrix3d reference_jacobian(const ElementNodes& X, const ShapeGradients& dNdxi) {
  return X.transpose() * dNdxi;
}

// Nonlinear strain-displacement matrix (header comment): columns 3a + i.
BMatrix nonlinear_b(const Eigen::Matrix3d& F, const ShapeGradients& G) {
  const int n = static_cast<int>(G.rows());
  BMatrix B(6, 3 * n);
  for (int a = 0; a < n; ++a) {
    const double g0 = G(a, 0), g1 = G(a, 1), g2 = G(a, 2);
    for (int i = 0; i < 3; ++i) {
      const int c = 3 * a + i;
      B(0, c) = F(i, 0) * g0;
      B(1, c) = F(i, 1) * g1;
      B(2, c) = F(i, 2) * g2;
      B(3, c) = F(i, 0) * g1 + F(i, 1) * g0;
      B(4, c) = F(i, 1) * g2 + F(i, 2) * g1;
      B(5, c) = F(i, 0) * g2 + F(i, 2) * g0;
    }
  }
  return B;
}

ElementResponse failed(ElementResponse r, ElementStatus status, int point) {
  r.status = status;
  r.failed_point = point;
  r.energy = 0.0;
  r.force.setZero();
  r.tangent.setZero();
  return r;
}

}  // namespace

ElementStatus element_geometry(ElementOrder order, const ElementNodes& X, ElementGeometry& geometry) {
  check_rows(order, X, "X");
  const QuadratureRule& rule = tet_stiffness_rule(order);
  geometry.grad.clear();
  geometry.dV.clear();
  for (const QuadraturePoint& qp : rule) {
    const ShapeGradients dNdxi = tet_shape_derivatives(order, qp.xi);
    const Eigen::Matrix3d Jref = reference_jacobian(X, dNdxi);
    const double det_ref = Jref.determinant();
    if (!(det_ref > 0.0) || !std::isfinite(det_ref)) {
      geometry.grad.clear();
      geometry.dV.clear();
      return ElementStatus::InvertedReference;
    }
    geometry.grad.push_back(dNdxi * Jref.inverse());  // dN_a/dX
    geometry.dV.push_back(qp.weight * det_ref);
  }
  return ElementStatus::Ok;
}

ElementResponse element_response(ElementOrder order, const ElementNodes& X, const ElementNodes& u,
                                 const HyperelasticLaw& law, ElementOutput what) {
  check_rows(order, u, "u");
  ElementGeometry geometry;
  ElementResponse r;
  const ElementStatus status = element_geometry(order, X, geometry);
  if (status != ElementStatus::Ok) {
    // Find the failing point for the report (the geometry stops at the first one).
    const int n = tet_node_count(order);
    if (what != ElementOutput::Energy) r.force = ElementVector::Zero(3 * n);
    if (what == ElementOutput::EnergyForceAndTangent) r.tangent = ElementMatrix::Zero(3 * n, 3 * n);
    r.min_J = std::numeric_limits<double>::infinity();
    const QuadratureRule& rule = tet_stiffness_rule(order);
    int q = 0;
    while (q < static_cast<int>(rule.size()) &&
           reference_jacobian(X, tet_shape_derivatives(order, rule[q].xi)).determinant() > 0.0)
      ++q;
    return failed(r, status, q);
  }
  return element_response(geometry, u, law, what);
}

ElementResponse element_response(const ElementGeometry& geometry, const ElementNodes& u, const HyperelasticLaw& law,
                                 ElementOutput what) {
  const int n = static_cast<int>(u.rows());
  const bool want_force = what != ElementOutput::Energy;
  const bool want_tangent = what == ElementOutput::EnergyForceAndTangent;

  ElementResponse r;
  if (want_force) r.force = ElementVector::Zero(3 * n);
  if (want_tangent) r.tangent = ElementMatrix::Zero(3 * n, 3 * n);
  r.min_J = std::numeric_limits<double>::infinity();

  for (int q = 0; q < static_cast<int>(geometry.dV.size()); ++q) {
    const ShapeGradients& G = geometry.grad[q];
    if (G.rows() != n) throw std::invalid_argument("element kernel: geometry and u differ in node count");
    const Eigen::Matrix3d F = Eigen::Matrix3d::Identity() + u.transpose() * G;
    if (!F.allFinite()) return failed(r, ElementStatus::NonFinite, q);
    const double J = F.determinant();
    r.min_J = std::min(r.min_J, J);
    if (!(J > 0.0)) return failed(r, ElementStatus::Inverted, q);

    const Eigen::Matrix3d C = F.transpose() * F;
    const double dV = geometry.dV[q];
    const double W = law.energy(C);
    if (!std::isfinite(W)) return failed(r, ElementStatus::NonFinite, q);
    r.energy += W * dV;
    if (!want_force) continue;

    const Eigen::Matrix3d S = law.pk2(C);
    if (!S.allFinite()) return failed(r, ElementStatus::NonFinite, q);
    Eigen::Matrix<double, 6, 1> Sv;
    Sv << S(0, 0), S(1, 1), S(2, 2), S(0, 1), S(1, 2), S(0, 2);
    const BMatrix B = nonlinear_b(F, G);
    r.force.noalias() += B.transpose() * (Sv * dV);
    if (!want_tangent) continue;

    const Tangent6 CC = law.tangent(C);
    if (!CC.allFinite()) return failed(r, ElementStatus::NonFinite, q);
    r.tangent.noalias() += B.transpose() * (CC * dV) * B;
    const ShapeGradients SG = G * (S * dV);  // row a: (S grad N_a)^T dV (S symmetric)
    for (int a = 0; a < n; ++a)
      for (int b = 0; b < n; ++b) {
        const double k = SG.row(a).dot(G.row(b));
        for (int i = 0; i < 3; ++i) r.tangent(3 * a + i, 3 * b + i) += k;
      }
  }
  return r;
}

ElementVector element_body_force(ElementOrder order, const ElementNodes& X, double density,
                                 const Eigen::Vector3d& acceleration) {
  check_rows(order, X, "X");
  const int n = tet_node_count(order);
  ElementVector f = ElementVector::Zero(3 * n);
  for (const QuadraturePoint& qp : tet_load_rule(order)) {
    const double det_ref = reference_jacobian(X, tet_shape_derivatives(order, qp.xi)).determinant();
    if (!(det_ref > 0.0))
      throw SolverError("element body force: non-positive reference Jacobian " + std::to_string(det_ref));
    const ShapeValues N = tet_shape_values(order, qp.xi);
    const Eigen::Vector3d b = density * acceleration * (qp.weight * det_ref);
    for (int a = 0; a < n; ++a) f.segment<3>(3 * a) += N(a) * b;
  }
  return f;
}

double element_reference_volume(ElementOrder order, const ElementNodes& X) {
  check_rows(order, X, "X");
  double V = 0.0;
  for (const QuadraturePoint& qp : tet_load_rule(order))
    V += qp.weight * reference_jacobian(X, tet_shape_derivatives(order, qp.xi)).determinant();
  return V;
}

}  // namespace tissuemesh
