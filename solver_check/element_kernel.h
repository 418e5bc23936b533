// Total-Lagrangian element routines of the built-in solver for tet4 and tet10 (Bonet & Wood,
// "Nonlinear Continuum Mechanics for Finite Element Analysis", 2nd ed., 2008; docs/solver.md).
//
// Units: the kernel is unit-agnostic; the caller passes consistent values. With a model in
// mm-t-s (lengths mm, law from make_law(spec, UnitSystem::MillimetreTonneSecond) in MPa, density
// in t/mm^3, acceleration in mm/s^2) forces come out in N and energies in N mm. In general:
//   force = stress x length^2, energy = stress x length^3, body force = density x acceleration x
//   length^3. Model nodes are stored in mm: convert them with length_from_mm(model.units, .)
//   before calling, and convert gravity with acceleration_from_m_per_s2 and density with
//   density_from_kg_per_m3 (core/unit_system.h).
//
// Shapes: X (reference coordinates) and u (displacements) are n x 3, one row per node in
// core/model.h's order (n = 4 or 10, see solver_check/tet_shape.h). Element vectors and matrices
// are ordered node-major: dof 3 a + i is component i (x, y, z) of node a.
//
// Formulation (total Lagrangian, reference configuration X):
//   F = I + du/dX, C = F^T F, S = law.pk2(C), CC = law.tangent(C) (Voigt 11,22,33,12,23,13).
//   energy   Pi = int W(C) dV
//   f_int    f_a = int B_a^T S_v dV = int (F S) grad N_a dV, with the nonlinear B_a (6 x 3):
//            rows 11: F_i1 N_a,1   22: F_i2 N_a,2   33: F_i3 N_a,3
//                 12: F_i1 N_a,2 + F_i2 N_a,1   23: F_i2 N_a,3 + F_i3 N_a,2   13: F_i1 N_a,3 + F_i3 N_a,1
//            (engineering shear in B, tensor shear S_v = (S11,S22,S33,S12,S23,S13)), so f = dPi/du.
//   tangent  K_ab = int B_a^T CC B_b dV  +  int (grad N_a . S grad N_b) dV I_3  (material +
//            geometric), K = d f_int / du, symmetric.
//   body     f_a = int N_a rho g dV over the reference volume (dead load, reference density).
// Quadrature: tet_stiffness_rule / tet_load_rule (tet_shape.h documents the choice and exactness).
//
// Failure: the response never contains NaN. When det(dX/dxi) <= 0 (inverted or flat reference
// element) or J = det F <= 0 or a non-finite value appears at a quadrature point, the status says
// which and where, energy is 0 and force/tangent are zero: the solver cuts the load step back (or
// refuses the model for an inverted reference). Nothing is thrown for these conditions.
#pragma once

#include "core/model.h"
#include "materials/hyperelastic_law.h"
#include "solver_check/tet_shape.h"

#include <Eigen/Core>

#include <vector>

namespace tissuemesh {

/// n x 3 nodal array (n = 4 or 10), one row per node.
using ElementNodes = Eigen::Matrix<double, Eigen::Dynamic, 3, 0, 10, 3>;
/// 3n element vector, node-major.
using ElementVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 30, 1>;
/// 3n x 3n element matrix, node-major.
using ElementMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 30, 30>;

enum class ElementStatus {
  Ok,
  InvertedReference,  ///< det(dX/dxi) <= 0 at a quadrature point: the mesh itself is invalid
  Inverted,           ///< J = det F <= 0 at a quadrature point: cut the load step back
  NonFinite,          ///< a non-finite F, energy, stress or tangent at a quadrature point
};

/// What element_response computes; energy is always computed.
enum class ElementOutput { Energy, EnergyAndForce, EnergyForceAndTangent };

struct ElementResponse {
  ElementStatus status = ElementStatus::Ok;
  int failed_point = -1;  ///< index into the stiffness rule of the first failing point, else -1
  double min_J = 0.0;     ///< smallest det F over the points evaluated (the failing one included)
  double energy = 0.0;    ///< stored energy, stress x length^3
  ElementVector force;    ///< f_int (3n), when requested; zero on failure
  ElementMatrix tangent;  ///< K (3n x 3n), when requested; zero on failure
  bool ok() const { return status == ElementStatus::Ok; }
};

/// Energy, internal force and tangent of one element at displacement u (see the header comment).
/// Throws std::invalid_argument only when X or u does not have tet_node_count(order) rows.
ElementResponse element_response(ElementOrder order, const ElementNodes& X, const ElementNodes& u,
                                 const HyperelasticLaw& law,
                                 ElementOutput what = ElementOutput::EnergyForceAndTangent);

/// What element_response needs of the reference element at each stiffness quadrature point: the
/// physical shape-function gradients dN/dX (n x 3, 1/length) and the volume weight
/// w_q det(dX/dxi) (length^3). Constant during a solve, so the solver computes it once.
struct ElementGeometry {
  std::vector<ShapeGradients> grad;  ///< one per point of tet_stiffness_rule(order)
  std::vector<double> dV;            ///< same length
};

/// The geometry of element X; status InvertedReference (geometry left empty) when det(dX/dxi) <= 0
/// or is not finite at a point. Throws std::invalid_argument on a wrong row count.
ElementStatus element_geometry(ElementOrder order, const ElementNodes& X, ElementGeometry& geometry);

/// element_response from precomputed geometry (u: one row per node, as above).
ElementResponse element_response(const ElementGeometry& geometry, const ElementNodes& u,
                                 const HyperelasticLaw& law,
                                 ElementOutput what = ElementOutput::EnergyForceAndTangent);

/// Consistent body force int N_a rho g dV (3n, node-major) over the reference element; exact for
/// straight elements. Throws SolverError on a non-positive reference Jacobian and
/// std::invalid_argument on a wrong row count.
ElementVector element_body_force(ElementOrder order, const ElementNodes& X, double density,
                                 const Eigen::Vector3d& acceleration);

/// Reference volume int dV of the element (sum of quadrature weights x det(dX/dxi)).
double element_reference_volume(ElementOrder order, const ElementNodes& X);

}  // namespace tissuemesh
