#include "solver_check/dof_map.h"

#include "core/errors.h"
#include "solver_check/static_solver.h"

#include <Eigen/Geometry>

#include <cmath>
#include <string>

namespace tissuemesh {

namespace {

// Below this (sin of the angle to the span already taken) a normal adds no new constraint: a node
// shared by two sliding sets on one plane (area-weighted normals agree to round-off) keeps its
// plane instead of losing a direction to noise.
constexpr double kParallel = 1e-8;

/// Orthonormal basis of the complement of span(normals); returns its dimension (3 - rank).
int allowed_directions(const std::vector<Eigen::Vector3d>& normals, Eigen::Matrix3d& basis) {
  std::vector<Eigen::Vector3d> taken;  // orthonormal basis of the constrained span
  for (const Eigen::Vector3d& n : normals) {
    Eigen::Vector3d r = n;
    for (const Eigen::Vector3d& t : taken) r -= r.dot(t) * t;
    if (r.norm() > kParallel * n.norm()) taken.push_back(r.normalized());
    if (taken.size() == 3) break;
  }
  basis.setZero();
  if (taken.empty()) {
    basis.setIdentity();
    return 3;
  }
  if (taken.size() == 1) {
    // Any orthonormal pair perpendicular to n: start from the axis least aligned with it.
    const Eigen::Vector3d& n = taken[0];
    Eigen::Index axis;
    n.cwiseAbs().minCoeff(&axis);
    Eigen::Vector3d t1 = Eigen::Vector3d::Unit(axis) - n[axis] * n;
    t1.normalize();
    basis.col(0) = t1;
    basis.col(1) = n.cross(t1);
    return 2;
  }
  if (taken.size() == 2) {
    basis.col(0) = taken[0].cross(taken[1]).normalized();
    return 1;
  }
  return 0;
}

}  // namespace

DofMap::DofMap(const Model& model, const std::vector<PrescribedDisplacement>& prescribed) {
  const int n = static_cast<int>(model.nodes.size());
  count_.assign(n, 3);
  first_.assign(n, -1);
  basis_.assign(n, Eigen::Matrix3d::Identity());
  prescribed_.assign(n, Eigen::Vector3d::Zero());

  std::vector<char> fixed(n, 0);
  std::vector<std::vector<Eigen::Vector3d>> normals(n);
  for (const NodeSet& set : model.node_sets) {
    if (set.constraint == Constraint::Fixed) {
      for (int v : set.nodes) fixed[v] = 1;
      continue;
    }
    if (set.normals.size() != set.nodes.size())
      throw InputError("sliding node set '" + set.name + "' needs one normal per node");
    for (std::size_t i = 0; i < set.nodes.size(); ++i) {
      const Eigen::Vector3d& nv = set.normals[i];
      if (!nv.allFinite() || std::abs(nv.norm() - 1.0) > 1e-6)
        throw InputError("sliding node set '" + set.name + "': normal of node " + std::to_string(set.nodes[i]) +
                         " is not a unit vector");
      normals[set.nodes[i]].push_back(nv);
    }
  }
  for (const PrescribedDisplacement& p : prescribed) {
    if (p.node < 0 || p.node >= n)
      throw InputError("prescribed displacement: node " + std::to_string(p.node) + " is not a model node (0.." +
                       std::to_string(n - 1) + ")");
    if (!p.value.allFinite())
      throw InputError("prescribed displacement of node " + std::to_string(p.node) + " is not finite");
    fixed[p.node] = 1;
    prescribed_[p.node] = p.value;
  }

  for (int v = 0; v < n; ++v) {
    if (fixed[v])
      count_[v] = 0;
    else if (!normals[v].empty())
      count_[v] = allowed_directions(normals[v], basis_[v]);
    if (count_[v] > 0) {
      first_[v] = num_free_;
      num_free_ += count_[v];
    }
    if (count_[v] < 3) constrained_.push_back(v);
  }
}

Eigen::VectorXd DofMap::expand(const Eigen::VectorXd& q, double lambda) const {
  Eigen::VectorXd u(3 * count_.size());
  for (int v = 0; v < num_nodes(); ++v) {
    Eigen::Vector3d uv = lambda * prescribed_[v];
    if (count_[v] == 3)  // identity basis
      uv += q.segment<3>(first_[v]);
    else
      for (int k = 0; k < count_[v]; ++k) uv += q[first_[v] + k] * basis_[v].col(k);
    u.segment<3>(3 * v) = uv;
  }
  return u;
}

Eigen::VectorXd DofMap::reduce(const Eigen::VectorXd& f) const {
  Eigen::VectorXd r(num_free_);
  for (int v = 0; v < num_nodes(); ++v)
    for (int k = 0; k < count_[v]; ++k) r[first_[v] + k] = basis_[v].col(k).dot(f.segment<3>(3 * v));
  return r;
}

Eigen::Vector3d DofMap::constrained_part(int v, const Eigen::Vector3d& f) const {
  Eigen::Vector3d r = f;
  for (int k = 0; k < count_[v]; ++k) r -= basis_[v].col(k).dot(f) * basis_[v].col(k);
  return r;
}

std::vector<int> DofMap::node_groups() const {
  std::vector<int> group(num_free_);
  int g = 0;
  for (int v = 0; v < num_nodes(); ++v) {
    if (count_[v] == 0) continue;
    for (int k = 0; k < count_[v]; ++k) group[first_[v] + k] = g;
    ++g;
  }
  return group;
}

}  // namespace tissuemesh
