#include "solver_check/cell_fields.h"

#include "core/errors.h"
#include "materials/make_law.h"
#include "materials/volumetric_split.h"
#include "solver_check/nodal_pressure.h"
#include "solver_check/tet_shape.h"

#include <Eigen/LU>

#include <cmath>
#include <memory>
#include <stdexcept>
#include <string>

namespace tissuemesh {

namespace {

StressVoigt to_voigt(const Eigen::Matrix3d& s) {
  StressVoigt v;
  v << s(0, 0), s(1, 1), s(2, 2), s(0, 1), s(1, 2), s(0, 2);
  return v;
}

std::string element_name(const Model& model, std::size_t e) {
  return "element " + std::to_string(e) + " (tissue '" + model.tissue_names.at(model.tissue_ids[e] - 1) + "')";
}

/// pbar_e (Pa) of every element of a nodal-pressure tet4 model at u (mm, 3 per node).
std::vector<double> nodal_pressures(const Model& model, const std::vector<const HyperelasticLaw*>& law,
                                    const Eigen::VectorXd& u_mm) {
  std::vector<ElementGeometry> geometry(model.elements.size());
  std::vector<int> tissue(model.elements.size());
  for (std::size_t e = 0; e < model.elements.size(); ++e) {
    ElementNodes X(4, 3);
    for (int a = 0; a < 4; ++a) X.row(a) = model.nodes[model.elements[e][a]].transpose();
    if (element_geometry(ElementOrder::Linear, X, geometry[e]) != ElementStatus::Ok)
      throw SolverError("cell fields: " + element_name(model, e) + " is inverted in the reference mesh");
    tissue[e] = model.tissue_ids[e] - 1;
  }
  const NodalPressure nodal(model.elements, geometry, tissue, law);
  const NodalPressure::State state = nodal.evaluate(u_mm, 1);
  if (!state.ok)
    throw SolverError("cell fields: " + (state.failed_element >= 0 ? element_name(model, state.failed_element)
                                                                    : std::string("a node patch")) +
                      " has J = " + std::to_string(state.failed_J) + " (inverted or non-finite state)");
  return state.pressure;
}

}  // namespace

double von_mises(const StressVoigt& s) {
  const double d01 = s[0] - s[1], d12 = s[1] - s[2], d20 = s[2] - s[0];
  return std::sqrt(0.5 * (d01 * d01 + d12 * d12 + d20 * d20) + 3.0 * (s[3] * s[3] + s[4] * s[4] + s[5] * s[5]));
}

CellFields cell_fields(const Model& model, const std::vector<Eigen::Vector3d>& displacements) {
  if (displacements.size() != model.nodes.size())
    throw std::invalid_argument("cell_fields: " + std::to_string(displacements.size()) + " displacements for " +
                                std::to_string(model.nodes.size()) + " nodes");
  // Laws in SI give Pa directly; F is dimensionless, so only the displacements need converting to
  // the millimetres the nodes are stored in (exact for the mm systems: division by 1).
  std::vector<std::unique_ptr<HyperelasticLaw>> laws;
  for (const MaterialSpec& spec : model.materials) laws.push_back(make_law(spec, UnitSystem::SI));
  const double length_per_mm = length_from_mm(model.units, 1.0);

  const ElementOrder order = model.order;
  // Nodal-pressure tet4: the element stress of W_rest plus pbar_e I (solver_check/nodal_pressure.h).
  const bool nodal = uses_nodal_pressure(model);
  std::vector<std::unique_ptr<HyperelasticLaw>> shear;
  std::vector<double> pressure(model.elements.size(), 0.0);
  if (nodal) {
    std::vector<const HyperelasticLaw*> law;
    for (std::size_t e = 0; e < model.elements.size(); ++e)
      law.push_back(laws.at(static_cast<std::size_t>(model.tissue_ids[e] - 1)).get());
    Eigen::VectorXd u_mm(3 * model.nodes.size());
    for (std::size_t v = 0; v < model.nodes.size(); ++v) u_mm.segment<3>(3 * v) = displacements[v] / length_per_mm;
    pressure = nodal_pressures(model, law, u_mm);
    for (const auto& l : laws) shear.push_back(make_shear_part(*l));
  }
  const int n = tet_node_count(order);
  const QuadratureRule& rule = tet_stiffness_rule(order);
  std::vector<ShapeGradients> dNdxi;
  for (const QuadraturePoint& qp : rule) dNdxi.push_back(tet_shape_derivatives(order, qp.xi));

  CellFields out;
  out.cauchy_stress_Pa.resize(model.elements.size());
  out.von_mises_Pa.resize(model.elements.size());
  out.J.resize(model.elements.size());
  Eigen::Matrix<double, Eigen::Dynamic, 3, 0, 10, 3> X(n, 3), u(n, 3);
  for (std::size_t e = 0; e < model.elements.size(); ++e) {
    for (int a = 0; a < n; ++a) {
      const int node = model.elements[e][a];
      X.row(a) = model.nodes[node].transpose();
      u.row(a) = (displacements[node] / length_per_mm).transpose();
    }
    const std::size_t t = static_cast<std::size_t>(model.tissue_ids[e] - 1);
    const HyperelasticLaw& law = nodal ? *shear.at(t) : *laws.at(t);
    Eigen::Matrix3d sigma_sum = Eigen::Matrix3d::Zero();
    double J_sum = 0.0, volume = 0.0;
    for (std::size_t q = 0; q < rule.size(); ++q) {
      const Eigen::Matrix3d Jref = X.transpose() * dNdxi[q];  // dX/dxi
      const double det_ref = Jref.determinant();
      if (!(det_ref > 0.0) || !std::isfinite(det_ref))
        throw SolverError("cell fields: " + element_name(model, e) + " is inverted in the reference mesh");
      const Eigen::Matrix3d F = Eigen::Matrix3d::Identity() + u.transpose() * (dNdxi[q] * Jref.inverse());
      const double J = F.determinant();
      if (!F.allFinite() || !(J > 0.0))
        throw SolverError("cell fields: " + element_name(model, e) + " has J = " + std::to_string(J) +
                          " at quadrature point " + std::to_string(q) + " (inverted or non-finite state)");
      const Eigen::Matrix3d sigma =
          F * law.pk2(F.transpose() * F) * F.transpose() / J + pressure[e] * Eigen::Matrix3d::Identity();
      if (!sigma.allFinite())
        throw SolverError("cell fields: " + element_name(model, e) + " has a non-finite stress");
      const double dV = rule[q].weight * det_ref;
      sigma_sum += sigma * dV;
      J_sum += J * dV;
      volume += dV;
    }
    out.cauchy_stress_Pa[e] = to_voigt(sigma_sum / volume);
    out.J[e] = J_sum / volume;
    out.von_mises_Pa[e] = von_mises(out.cauchy_stress_Pa[e]);
  }
  return out;
}

}  // namespace tissuemesh
