// DofMap: the unknowns of the built-in solver after the model's constraints (docs/solver.md,
// "Constraints").
//
// Every node v has a reduced basis: the k_v orthonormal directions (columns of basis(v), 3 x 3,
// the first k_v used) in which it may move, k_v in {0, 1, 2, 3}:
//   free node                      k = 3, basis = identity (the common case, no transformation)
//   node of a Sliding set, normal n   k = 2, basis spans the plane n . u = 0
//   two non-parallel sliding normals  k = 1, the line along n1 x n2
//   three independent normals, a Fixed set, or a prescribed node   k = 0
// Its displacement is u_v = basis(v).leftCols(k_v) q_v + lambda * prescribed_v, with q_v the k_v
// reduced unknowns, numbered node by node (node order, so the model's RCM numbering carries over).
// Normals within 1e-8 (in sin of the angle) of the span of those already taken are dropped as
// duplicates, so a node on two coplanar sliding sets keeps its plane.
// The reaction at a node is the part of f_int - lambda f_ext outside its reduced basis:
// (I - B B^T)(f_int - lambda f_ext) with B = basis(v).leftCols(k_v).
#pragma once

#include "core/model.h"

#include <Eigen/Core>

#include <vector>

namespace tissuemesh {

struct PrescribedDisplacement;

class DofMap {
 public:
  /// Throws InputError for a prescribed node index out of range or a non-finite value, and for a
  /// sliding set whose normals are missing or not unit length (validate_model checks the model's).
  DofMap(const Model& model, const std::vector<PrescribedDisplacement>& prescribed);

  int num_nodes() const { return static_cast<int>(count_.size()); }
  int num_free() const { return num_free_; }
  /// Reduced unknowns of node v: count(v) of them starting at first(v) (first = -1 when count 0).
  int count(int v) const { return count_[v]; }
  int first(int v) const { return first_[v]; }
  /// True when node v is free in all three directions with the identity basis.
  bool unconstrained(int v) const { return count_[v] == 3; }
  /// Columns 0..count(v)-1: the allowed directions of node v (orthonormal).
  const Eigen::Matrix3d& basis(int v) const { return basis_[v]; }
  /// Nodes with count < 3 (fixed, sliding or prescribed), sorted.
  const std::vector<int>& constrained_nodes() const { return constrained_; }

  /// Group of each reduced unknown: the index of its node among the nodes with count > 0 (0, 1, ...
  /// in unknown order), for SparseSpdSolver's ordering of a node's unknowns together.
  std::vector<int> node_groups() const;
  /// Global displacement (3 per node) of reduced unknowns q at load factor lambda.
  Eigen::VectorXd expand(const Eigen::VectorXd& q, double lambda) const;
  /// Reduced part B^T f of a global nodal vector f (3 per node).
  Eigen::VectorXd reduce(const Eigen::VectorXd& f) const;
  /// Constrained part (I - B B^T) f_v of node v's 3-vector.
  Eigen::Vector3d constrained_part(int v, const Eigen::Vector3d& f) const;

 private:
  std::vector<int> count_, first_;
  std::vector<Eigen::Matrix3d> basis_;
  std::vector<Eigen::Vector3d> prescribed_;  ///< lambda = 1 value per node (zero unless prescribed)
  std::vector<int> constrained_;
  int num_free_ = 0;
};

}  // namespace tissuemesh
