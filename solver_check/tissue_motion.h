// How each tissue moved in a solved state: volume-mean displacement of every tissue and the
// largest nodal displacement — the figures a prone/supine study reports (e.g. the tumour's
// displacement).
//
// Input: the model and one displacement per model node in the model's length unit (as
// SolveResult::displacements); all outputs are in millimetres.
//
// Per tissue T (reference configuration, straight elements):
//   V_T = int_T dV,  centroid_T = int_T X dV / V_T,  mean displacement_T = int_T u dV / V_T,
// with u and X interpolated by the element shape functions (tet_shape.h). The integrals are exact
// through the integrals of the shape functions over a straight tet of volume V:
//   tet4  int N_a dV = V/4 for each corner;
//   tet10 int N_a dV = -V/20 for each corner, V/5 for each midside node.
// So a uniform translation t gives t for every tissue, and u = A X gives A centroid_T.
#pragma once

#include "core/model.h"

#include <Eigen/Core>

#include <string>
#include <vector>

namespace tissuemesh {

struct TissueMotion {
  std::string name;
  double volume_mm3 = 0.0;                                            ///< reference volume
  Eigen::Vector3d centroid_mm = Eigen::Vector3d::Zero();              ///< reference centroid, LPS mm
  Eigen::Vector3d mean_displacement_mm = Eigen::Vector3d::Zero();     ///< int u dV / V, mm
};

struct MotionSummary {
  std::vector<TissueMotion> tissues;  ///< one per tissue, in model.tissue_names order
  double max_displacement_mm = 0.0;   ///< largest |u| over all nodes
  int max_displacement_node = -1;     ///< its 0-based model node (the lowest index on ties); -1 if no nodes
};

/// Throws std::invalid_argument when displacements.size() != model.nodes.size(). A tissue
/// without elements has volume 0 and zero centroid and mean displacement.
MotionSummary tissue_motion(const Model& model, const std::vector<Eigen::Vector3d>& displacements);

}  // namespace tissuemesh
