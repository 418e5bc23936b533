#include "solver_check/tet_shape.h"

#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

namespace tissuemesh {

namespace {

// Midside m = 4..9 joins corners kEdge[m - 4] (model.h).
constexpr int kEdge[6][2] = {{0, 1}, {1, 2}, {2, 0}, {0, 3}, {1, 3}, {2, 3}};

// Barycentric coordinates and their constant derivatives with respect to (r, s, t).
std::array<double, 4> barycentric(const Eigen::Vector3d& xi) {
  return {1.0 - xi(0) - xi(1) - xi(2), xi(0), xi(1), xi(2)};
}

Eigen::Vector3d barycentric_gradient(int a) {
  return a == 0 ? Eigen::Vector3d(-1.0, -1.0, -1.0) : Eigen::Vector3d::Unit(a - 1);
}

QuadratureRule make_rule(int degree) {
  if (degree == 1) return {{Eigen::Vector3d::Constant(0.25), 1.0 / 6.0}};
  const double a = (5.0 + 3.0 * std::sqrt(5.0)) / 20.0;
  const double b = (5.0 - std::sqrt(5.0)) / 20.0;
  // Point k has barycentric coordinate a at corner k and b at the other three.
  QuadratureRule rule;
  for (int k = 0; k < 4; ++k) {
    std::array<double, 4> L;
    L.fill(b);
    L[k] = a;
    rule.push_back({Eigen::Vector3d(L[1], L[2], L[3]), 1.0 / 24.0});
  }
  return rule;
}

}  // namespace

int tet_node_count(ElementOrder order) { return order == ElementOrder::Linear ? 4 : 10; }

Eigen::Vector3d tet_node_xi(ElementOrder order, int a) {
  if (a < 0 || a >= tet_node_count(order)) throw std::invalid_argument("tet_node_xi: node " + std::to_string(a));
  auto corner = [](int c) { return c == 0 ? Eigen::Vector3d::Zero().eval() : Eigen::Vector3d::Unit(c - 1).eval(); };
  if (a < 4) return corner(a);
  return 0.5 * (corner(kEdge[a - 4][0]) + corner(kEdge[a - 4][1]));
}

ShapeValues tet_shape_values(ElementOrder order, const Eigen::Vector3d& xi) {
  const auto L = barycentric(xi);
  ShapeValues N(tet_node_count(order));
  if (order == ElementOrder::Linear) {
    for (int a = 0; a < 4; ++a) N(a) = L[a];
    return N;
  }
  for (int a = 0; a < 4; ++a) N(a) = L[a] * (2.0 * L[a] - 1.0);
  for (int m = 0; m < 6; ++m) N(4 + m) = 4.0 * L[kEdge[m][0]] * L[kEdge[m][1]];
  return N;
}

ShapeGradients tet_shape_derivatives(ElementOrder order, const Eigen::Vector3d& xi) {
  const auto L = barycentric(xi);
  ShapeGradients dN(tet_node_count(order), 3);
  if (order == ElementOrder::Linear) {
    for (int a = 0; a < 4; ++a) dN.row(a) = barycentric_gradient(a).transpose();
    return dN;
  }
  for (int a = 0; a < 4; ++a) dN.row(a) = (4.0 * L[a] - 1.0) * barycentric_gradient(a).transpose();
  for (int m = 0; m < 6; ++m) {
    const int i = kEdge[m][0], j = kEdge[m][1];
    dN.row(4 + m) = 4.0 * (L[j] * barycentric_gradient(i) + L[i] * barycentric_gradient(j)).transpose();
  }
  return dN;
}

const QuadratureRule& tet_quadrature(int degree) {
  static const QuadratureRule rule1 = make_rule(1);
  static const QuadratureRule rule2 = make_rule(2);
  if (degree == 1) return rule1;
  if (degree == 2) return rule2;
  throw std::invalid_argument("tet_quadrature: no rule of degree " + std::to_string(degree));
}

const QuadratureRule& tet_stiffness_rule(ElementOrder order) {
  return tet_quadrature(order == ElementOrder::Linear ? 1 : 2);
}

const QuadratureRule& tet_load_rule(ElementOrder order) {
  return tet_quadrature(order == ElementOrder::Linear ? 1 : 2);
}

}  // namespace tissuemesh
