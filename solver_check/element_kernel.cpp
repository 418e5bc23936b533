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

void check_rows(ElementOrder order, const ElementNodes& M, const char* what) {
  if (M.rows() != tet_node_count(order))
    throw std::invalid_argument(std::string("element kernel: ") + what + " has " + std::to_string(M.rows()) +
                                " rows, expected " + std::to_string(tet_node_count(order)));
}

// Jacobian dX/dxi (J_ij = dX_i/dxi_j) of the isoparametric map at a point with derivatives dNdxi.
Eigen::Matrix3d reference_jacobian(const ElementNodes& X, const ShapeGradients& dNdxi) {
  return X.transpose() * dNdxi;
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

namespace {

/// element_response for N nodes with fixed-size matrices: Eigen then multiplies the 6 x 3N strain
/// matrices inline instead of through its general (blocked, dynamic-size) matrix product, which
/// dominated the assembly with dynamic sizes.
template <int N>
ElementResponse fixed_size_response(const ElementGeometry& geometry, const ElementNodes& u, const HyperelasticLaw& law,
                                    ElementOutput what) {
  constexpr int D = 3 * N;
  const bool want_force = what != ElementOutput::Energy;
  const bool want_tangent = what == ElementOutput::EnergyForceAndTangent;

  ElementResponse r;
  r.min_J = std::numeric_limits<double>::infinity();
  // On failure: zero energy, and a zero force and tangent of the requested sizes.
  const auto fail = [&](ElementStatus status, int q) {
    if (want_force) r.force = ElementVector::Zero(D);
    if (want_tangent) r.tangent = ElementMatrix::Zero(D, D);
    return failed(r, status, q);
  };
  Eigen::Matrix<double, D, 1> force = Eigen::Matrix<double, D, 1>::Zero();
  Eigen::Matrix<double, D, D> tangent;
  if (want_tangent) tangent.setZero();
  const Eigen::Matrix<double, N, 3> ue = u;
  Eigen::Matrix3d S;
  Tangent6 CC;

  for (int q = 0; q < static_cast<int>(geometry.dV.size()); ++q) {
    if (geometry.grad[q].rows() != N) throw std::invalid_argument("element kernel: geometry and u differ in node count");
    const Eigen::Matrix<double, N, 3> G = geometry.grad[q];
    const Eigen::Matrix3d F = Eigen::Matrix3d::Identity() + ue.transpose() * G;
    if (!F.allFinite()) return fail(ElementStatus::NonFinite, q);
    const double J = F.determinant();
    r.min_J = std::min(r.min_J, J);
    if (!(J > 0.0)) return fail(ElementStatus::Inverted, q);

    const Eigen::Matrix3d C = F.transpose() * F;
    const double dV = geometry.dV[q];
    // One call for W, S and CC (the law computes its invariants of C once).
    const double W = law.evaluate(C, want_force ? &S : nullptr, want_tangent ? &CC : nullptr);
    if (!std::isfinite(W)) return fail(ElementStatus::NonFinite, q);
    r.energy += W * dV;
    if (!want_force) continue;

    if (!S.allFinite()) return fail(ElementStatus::NonFinite, q);
    Eigen::Matrix<double, 6, 1> Sv;
    Sv << S(0, 0), S(1, 1), S(2, 2), S(0, 1), S(1, 2), S(0, 2);
    Eigen::Matrix<double, 6, D> B;  // nonlinear strain-displacement matrix (header comment)
    for (int a = 0; a < N; ++a) {
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
    force.noalias() += B.transpose() * (Sv * dV);
    if (!want_tangent) continue;

    if (!CC.allFinite()) return fail(ElementStatus::NonFinite, q);
    const Eigen::Matrix<double, D, 6> BtC = B.transpose() * (CC * dV);
    tangent.noalias() += BtC.lazyProduct(B);
    const Eigen::Matrix<double, N, N> GSG = G * (S * dV) * G.transpose();  // grad N_a . S grad N_b dV
    for (int a = 0; a < N; ++a)
      for (int b = 0; b < N; ++b)
        for (int i = 0; i < 3; ++i) tangent(3 * a + i, 3 * b + i) += GSG(a, b);
  }
  if (want_force) r.force = force;
  if (want_tangent) r.tangent = tangent;
  return r;
}

}  // namespace

ElementResponse element_response(const ElementGeometry& geometry, const ElementNodes& u, const HyperelasticLaw& law,
                                 ElementOutput what) {
  switch (u.rows()) {
    case 4: return fixed_size_response<4>(geometry, u, law, what);
    case 10: return fixed_size_response<10>(geometry, u, law, what);
    default:
      throw std::invalid_argument("element kernel: u has " + std::to_string(u.rows()) + " rows, expected 4 or 10");
  }
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
