#include "support/support_load.h"

#include <set>

namespace tissuemesh::test {

SupportLoad support_load(const Model& model, const std::vector<int>& set) {
  const Eigen::Vector3d g = model.gravity.acceleration_m_s2 * acceleration_from_m_per_s2(model.units, 1.0);
  const std::set<int> in_set(set.begin(), set.end());
  const bool linear = model.order == ElementOrder::Linear;
  SupportLoad w;
  for (std::size_t e = 0; e < model.elements.size(); ++e) {
    const double rho = density_from_kg_per_m3(model.units, model.materials[model.tissue_ids[e] - 1].density_kg_m3);
    const Eigen::Vector3d f = rho * element_volume(model, e) * g;
    w.total += f;
    for (int k = 0; k < model.nodes_per_element(); ++k)
      if (in_set.count(model.elements[e][k])) w.on_set += f * (linear ? 0.25 : (k < 4 ? -0.05 : 0.2));
  }
  return w;
}

}  // namespace tissuemesh::test
