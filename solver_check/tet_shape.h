// Tetrahedral shape functions and quadrature rules for the built-in solver (docs/solver.md,
// "Elements").
//
// Reference (natural) tetrahedron: xi = (r, s, t), r, s, t >= 0, r + s + t <= 1, volume 1/6, with
// barycentric coordinates L0 = 1 - r - s - t, L1 = r, L2 = s, L3 = t, so that corner a sits at
// L_a = 1. Node order is core/model.h's (VTK, Abaqus C3D4/C3D10, FEBio):
//   tet4  corners 0..3:                       N_a = L_a
//   tet10 corners 0..3:                       N_a = L_a (2 L_a - 1)
//         midsides 4..9 of edges (0,1) (1,2) (2,0) (0,3) (1,3) (2,3):   N_m = 4 L_i L_j
// A positively oriented element ((X1-X0).((X2-X0)x(X3-X0)) > 0, model.h) has det(dX/dxi) > 0.
//
// Quadrature rules integrate over the reference tetrahedron; their weights sum to 1/6, so that
// sum_q w_q det(dX/dxi)(xi_q) f(xi_q) approximates the integral of f over the physical element.
//   degree 1: 1 point (the centroid, weight 1/6): exact for polynomials of degree <= 1 in xi.
//   degree 2: 4 symmetric points (a, b, b) ... with a = (5 + 3 sqrt5)/20, b = (5 - sqrt5)/20,
//             weights 1/24 (Hammer-Marlowe-Stroud; Abaqus C3D10's rule): exact for degree <= 2.
// Which rule each element uses (stiffness_rule, load_rule):
//   tet4  stiffness and load: degree 1. For a straight tet4, grad N is constant, so F, S and the
//         integrands of f_int and K are constant: the 1-point rule is exact at any strain. The
//         body-force integrand N_a rho g is linear: exact too.
//   tet10 stiffness: degree 2 (4 points). On a straight tet10, grad N is linear, so the small-strain
//         stiffness B^T D B is quadratic and integrated exactly; at finite strain the integrand is
//         not polynomial and the rule is the usual (Abaqus/CalculiX C3D10) approximation. 4 points x
//         6 strain components = 24 = 30 dofs - 6 rigid modes: no spurious zero-energy mode.
//   tet10 load: degree 2 (4 points): N_a rho g is quadratic, so the consistent body force is exact
//         (-1/20 of rho V g at each corner, 1/5 at each midside). A consistent mass matrix (N_a N_b,
//         degree 4) would NOT be integrated exactly by it; the static solver needs no mass matrix.
#pragma once

#include "core/model.h"

#include <Eigen/Core>

#include <vector>

namespace tissuemesh {

/// Shape-function values, one per node (4 or 10).
using ShapeValues = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 10, 1>;
/// Shape-function derivatives, one row per node: row a = (dN_a/dr, dN_a/ds, dN_a/dt), or, after
/// mapping, the physical gradient (dN_a/dX, dN_a/dY, dN_a/dZ) in 1/length.
using ShapeGradients = Eigen::Matrix<double, Eigen::Dynamic, 3, 0, 10, 3>;

struct QuadraturePoint {
  Eigen::Vector3d xi;  ///< natural coordinates (r, s, t)
  double weight;       ///< reference-tetrahedron weight; a rule's weights sum to 1/6
};
using QuadratureRule = std::vector<QuadraturePoint>;

/// 4 (Linear) or 10 (Quadratic).
int tet_node_count(ElementOrder order);

/// Natural coordinates of node a (corners at the unit vertices, midsides at edge midpoints).
Eigen::Vector3d tet_node_xi(ElementOrder order, int a);

/// N_a(xi) for every node, in model.h's order.
ShapeValues tet_shape_values(ElementOrder order, const Eigen::Vector3d& xi);

/// dN_a/dxi for every node (n x 3).
ShapeGradients tet_shape_derivatives(ElementOrder order, const Eigen::Vector3d& xi);

/// The rule exact for polynomials of total degree <= `degree` (1 or 2; throws std::invalid_argument
/// otherwise). The returned reference stays valid for the program's lifetime.
const QuadratureRule& tet_quadrature(int degree);

/// The rules the element kernel uses (see the table at the top): stiffness/internal force/energy,
/// and consistent body force.
const QuadratureRule& tet_stiffness_rule(ElementOrder order);
const QuadratureRule& tet_load_rule(ElementOrder order);

}  // namespace tissuemesh
