// Per-element results of a solved state: Cauchy stress, J = det F and von Mises stress of every
// element, for solution files and reports (docs/formats.md, "VTU": solution.vtu).
//
// Input: the model and one displacement per model node in the model's length unit
// (length_unit(model.units): mm for mm-t-s and mm-kg-s, m for SI), i.e. SolveResult::displacements
// as solve_static returns them.
//
// Per element e, at each point q of its stiffness rule (tet_stiffness_rule: 1 point for tet4,
// 4 for tet10; solver_check/tet_shape.h), with F = I + du/dX, J = det F, C = F^T F and S the
// second Piola-Kirchhoff stress of the element's tissue law (materials/make_law.h):
//   sigma_q = J^-1 F S F^T   (Cauchy stress)
// and the element value is the reference-volume-weighted mean over the points,
//   sigma_e = sum_q w_q det(dX/dxi)_q sigma_q / sum_q w_q det(dX/dxi)_q   (likewise J_e),
// the same weights the solver integrates with. For tet4 (F constant) it is the value itself; for a
// straight tet10 under a homogeneous deformation every point has the same value.
// A nodal-pressure tet4 model (model.analysis.tet4_pressure: nodal) has instead
//   sigma_e = J^-1 F S_rest F^T + pbar_e I,
// S_rest the stress of the law without its volumetric part, pbar_e the element's mean nodal
// pressure (solver_check/nodal_pressure.h), as the solver integrates it; under a homogeneous
// deformation it is the same stress.
// The von Mises stress is that of the mean Cauchy stress:
//   sqrt(1/2 ((s11-s22)^2 + (s22-s33)^2 + (s33-s11)^2) + 3 (s12^2 + s23^2 + s13^2)).
//
// Units: stresses in Pa whatever model.units is (laws are evaluated in SI, F is dimensionless).
#pragma once

#include "core/model.h"

#include <Eigen/Core>

#include <vector>

namespace tissuemesh {

/// Symmetric stress in Voigt order (xx, yy, zz, xy, yz, xz): tensor components, no factor 2.
using StressVoigt = Eigen::Matrix<double, 6, 1>;

struct CellFields {
  std::vector<StressVoigt> cauchy_stress_Pa;  ///< per element (model order): mean Cauchy stress, Pa
  std::vector<double> von_mises_Pa;           ///< per element: von Mises stress of that mean, Pa
  std::vector<double> J;                      ///< per element: mean det F (deformed / reference volume)
};

/// The fields of every element at `displacements` (one per model node, model length unit).
/// Throws std::invalid_argument when displacements.size() != model.nodes.size(); SolverError
/// naming the element (model index, 0-based, and tissue) when a point has J <= 0, a non-finite F
/// or a non-finite stress (a state solve_static never accepts) or the reference element is
/// inverted. The result never contains NaN.
CellFields cell_fields(const Model& model, const std::vector<Eigen::Vector3d>& displacements);

/// von Mises stress of a symmetric stress in Voigt order (header formula).
double von_mises(const StressVoigt& s);

}  // namespace tissuemesh
