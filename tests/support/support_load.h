// The weight of a model and the part of it its consistent nodal body load puts directly on a node
// set: what a support-reaction check against CalculiX needs (ccx's RF at fixed nodes is the
// internal force only, so the load sitting on those nodes must be added back).
#pragma once

#include "core/model.h"

#include <Eigen/Core>

#include <vector>

namespace tissuemesh::test {

struct SupportLoad {
  Eigen::Vector3d total = Eigen::Vector3d::Zero();   ///< sum of rho V g, model force unit
  Eigen::Vector3d on_set = Eigen::Vector3d::Zero();  ///< share on the nodes of the set
};

/// tet4: V/4 per corner; tet10: -V/20 per corner and V/5 per midside node (the integrals of the
/// quadratic shape functions over the tet). Units: the model's (N for mm-t-s).
SupportLoad support_load(const Model& model, const std::vector<int>& set);

}  // namespace tissuemesh::test
