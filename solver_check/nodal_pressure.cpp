#include "solver_check/nodal_pressure.h"

#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <stdexcept>
#include <utility>

namespace tissuemesh {

bool uses_nodal_pressure(const Model& model) {
  return model.order == ElementOrder::Linear && model.analysis.tet4_pressure == Tet4Pressure::Nodal;
}

NodalPressure::NodalPressure(const std::vector<std::array<int, 10>>& elements,
                             const std::vector<ElementGeometry>& geometry, const std::vector<int>& tissue,
                             const std::vector<const HyperelasticLaw*>& law)
    : elements_(elements), geometry_(geometry) {
  const std::size_t ne = elements.size();
  if (geometry.size() != ne || tissue.size() != ne || law.size() != ne)
    throw std::invalid_argument("nodal pressure: elements, geometry, tissue and law differ in size");
  for (const ElementGeometry& g : geometry)
    if (g.dV.size() != 1 || g.grad.front().rows() != 4)
      throw std::invalid_argument("nodal pressure: needs tet4 elements with a 1-point rule");

  // Patches in order of first appearance of (node, tissue).
  std::map<std::pair<int, int>, int> index;
  corner_patch_.resize(ne);
  std::vector<std::vector<int>> members;  // elements of each patch, ascending by construction
  for (std::size_t e = 0; e < ne; ++e)
    for (int a = 0; a < 4; ++a) {
      const auto [it, fresh] = index.emplace(std::make_pair(elements[e][a], tissue[e]), static_cast<int>(members.size()));
      if (fresh) {
        members.emplace_back();
        patch_volume_.push_back(0.0);
        patch_law_.push_back(law[e]);
      }
      const int p = it->second;
      corner_patch_[e][a] = p;
      members[p].push_back(static_cast<int>(e));
      patch_volume_[p] += geometry[e].dV[0] / 4.0;
    }
  element_start_.assign(1, 0);
  node_start_.assign(1, 0);
  for (const std::vector<int>& m : members) {
    patch_elements_.insert(patch_elements_.end(), m.begin(), m.end());
    element_start_.push_back(static_cast<int>(patch_elements_.size()));
    std::vector<int> nodes;
    for (int e : m) nodes.insert(nodes.end(), elements[e].begin(), elements[e].begin() + 4);
    std::sort(nodes.begin(), nodes.end());
    nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
    for (int e : m) {
      std::array<int, 4> local;
      for (int b = 0; b < 4; ++b)
        local[b] = static_cast<int>(std::lower_bound(nodes.begin(), nodes.end(), elements[e][b]) - nodes.begin());
      corner_in_patch_.push_back(local);
    }
    patch_nodes_.insert(patch_nodes_.end(), nodes.begin(), nodes.end());
    node_start_.push_back(static_cast<int>(patch_nodes_.size()));
  }
}

NodalPressure::State NodalPressure::evaluate(const Eigen::VectorXd& u, int threads) const {
  const int ne = static_cast<int>(elements_.size());
  const int np = num_patches();
  State s;
  s.dv.resize(ne);
  s.volume.resize(ne);
  s.pressure.resize(ne);
  s.J.resize(np);
  s.stiffness.resize(np);
  std::vector<double> det(ne);
#pragma omp parallel for num_threads(threads) schedule(static)
  for (int e = 0; e < ne; ++e) {
    const ShapeGradients& G = geometry_[e].grad[0];
    Eigen::Matrix<double, 4, 3> ue;
    for (int a = 0; a < 4; ++a) ue.row(a) = u.segment<3>(3 * elements_[e][a]).transpose();
    const Eigen::Matrix3d F = Eigen::Matrix3d::Identity() + ue.transpose() * G;
    det[e] = F.determinant();
    if (!(det[e] > 0.0) || !F.allFinite()) continue;
    s.volume[e] = geometry_[e].dV[0] * det[e];
    // dv/dx_b = v F^-T grad N_b: row b of G F^-1, times v.
    s.dv[e] = (G * F.inverse()) * s.volume[e];
  }
  for (int e = 0; e < ne; ++e)
    if (!(det[e] > 0.0) || !std::isfinite(det[e])) {
      s.ok = false;
      s.failed_element = e;
      s.failed_J = det[e];
      return s;
    }
  std::vector<double> dU(np), energy(np);
#pragma omp parallel for num_threads(threads) schedule(static)
  for (int p = 0; p < np; ++p) {
    double v = 0.0;
    for (int k = element_start_[p]; k < element_start_[p + 1]; ++k) v += s.volume[patch_elements_[k]] / 4.0;
    s.J[p] = v / patch_volume_[p];
    const HyperelasticLaw::Volumetric vol = patch_law_[p]->volumetric(s.J[p]);
    dU[p] = vol.dU;
    energy[p] = patch_volume_[p] * vol.U;
    s.stiffness[p] = vol.d2U / patch_volume_[p];
  }
  for (int p = 0; p < np; ++p) s.energy += energy[p];  // in patch order: deterministic
  for (int e = 0; e < ne; ++e) {
    double sum = 0.0;
    for (int a = 0; a < 4; ++a) sum += dU[corner_patch_[e][a]];
    s.pressure[e] = sum / 4.0;
  }
  if (!std::isfinite(s.energy)) {
    s.ok = false;  // failed_element stays -1: every element is fine, U(J_p) is not
    s.failed_J = std::numeric_limits<double>::quiet_NaN();
  }
  return s;
}

void NodalPressure::add_element_terms(const State& s, int e, ElementVector& force, ElementMatrix* tangent) const {
  const double p = s.pressure[e];
  const Eigen::Matrix<double, 4, 3>& dv = s.dv[e];
  for (int b = 0; b < 4; ++b) force.segment<3>(3 * b) += p * dv.row(b).transpose();
  if (tangent == nullptr) return;
  const double c = p / s.volume[e];
  for (int b = 0; b < 4; ++b)
    for (int d = 0; d < 4; ++d) {
      if (b == d) continue;  // v is linear in each node's position
      const Eigen::Matrix3d block = c * (dv.row(b).transpose() * dv.row(d) - dv.row(d).transpose() * dv.row(b));
      tangent->block<3, 3>(3 * b, 3 * d) += block;
    }
}

void NodalPressure::patch_gradient(const State& s, int p, std::vector<Eigen::Vector3d>& d) const {
  d.assign(patch_nodes_end(p) - patch_nodes_begin(p), Eigen::Vector3d::Zero());
  for (int k = element_start_[p]; k < element_start_[p + 1]; ++k)
    for (int b = 0; b < 4; ++b) d[corner_in_patch_[k][b]] += s.dv[patch_elements_[k]].row(b).transpose() / 4.0;
}

}  // namespace tissuemesh
