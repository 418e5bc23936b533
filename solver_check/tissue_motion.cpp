#include "solver_check/tissue_motion.h"

#include <stdexcept>

namespace tissuemesh {

MotionSummary tissue_motion(const Model& model, const std::vector<Eigen::Vector3d>& displacements) {
  if (displacements.size() != model.nodes.size())
    throw std::invalid_argument("tissue_motion: " + std::to_string(displacements.size()) + " displacements for " +
                                std::to_string(model.nodes.size()) + " nodes");
  const double mm_per_length = 1.0 / length_from_mm(model.units, 1.0);  // exact: 1 or 1000

  MotionSummary out;
  for (const std::string& name : model.tissue_names) out.tissues.push_back({name});
  std::vector<Eigen::Vector3d> int_X(model.tissue_names.size(), Eigen::Vector3d::Zero());
  std::vector<Eigen::Vector3d> int_u(model.tissue_names.size(), Eigen::Vector3d::Zero());

  // Shape-function integrals as fractions of the element volume (header).
  const bool quadratic = model.order == ElementOrder::Quadratic;
  const int n = model.nodes_per_element();
  for (std::size_t e = 0; e < model.elements.size(); ++e) {
    const std::size_t t = static_cast<std::size_t>(model.tissue_ids[e] - 1);
    const double V = element_volume(model, e);
    out.tissues[t].volume_mm3 += V;
    for (int a = 0; a < n; ++a) {
      const double w = quadratic ? (a < 4 ? -V / 20.0 : V / 5.0) : V / 4.0;
      const int node = model.elements[e][a];
      int_X[t] += w * model.nodes[node];
      int_u[t] += w * displacements[node];
    }
  }
  for (std::size_t t = 0; t < out.tissues.size(); ++t) {
    TissueMotion& m = out.tissues[t];
    if (!(m.volume_mm3 > 0.0)) continue;
    m.centroid_mm = int_X[t] / m.volume_mm3;
    m.mean_displacement_mm = int_u[t] / m.volume_mm3 * mm_per_length;
  }
  for (std::size_t i = 0; i < displacements.size(); ++i) {
    const double d = displacements[i].norm() * mm_per_length;
    if (out.max_displacement_node < 0 || d > out.max_displacement_mm) {
      out.max_displacement_mm = d;
      out.max_displacement_node = static_cast<int>(i);
    }
  }
  return out;
}

}  // namespace tissuemesh
