// Comparing two nodal displacement fields of the same model (e.g. the built-in solver against
// CalculiX on the same deck): the figures of `check --calculix` (docs/verification.md, "Solver:
// agreement with CalculiX"). Pure arithmetic, no I/O.
//
// With u_ref the reference field (CalculiX) and u the other (built-in), per node i
//   d_i = |u_i - u_ref,i|    (Euclidean norm of the 3-vector difference)
// and the relative figures are taken against the reference's largest displacement:
//   max_diff_rel  = max_i d_i / max_i |u_ref,i|
//   mean_diff_rel = (sum_i d_i / n) / max_i |u_ref,i|
// Lengths are in whatever unit the fields are in (the model's length unit).
#pragma once

#include <Eigen/Core>

#include <vector>

namespace tissuemesh {

struct SolutionComparison {
  double max_diff = 0.0;           ///< max_i |u_i - u_ref,i|, length unit of the fields
  double mean_diff = 0.0;          ///< mean_i |u_i - u_ref,i|
  int max_diff_node = -1;          ///< 0-based node of max_diff (the first one on ties)
  double max_u_reference = 0.0;    ///< max_i |u_ref,i|
  double max_u_other = 0.0;        ///< max_i |u_i|
  /// max_diff / max_u_reference (and mean_diff / max_u_reference); when the reference does not
  /// move at all: 0 if the other does not either, +infinity otherwise.
  double max_diff_rel = 0.0;
  double mean_diff_rel = 0.0;
};

/// Compares `other` with `reference`, node by node. Throws InputError when the two have different
/// sizes, are empty, or hold a non-finite component (naming the node, 0-based).
SolutionComparison compare_solutions(const std::vector<Eigen::Vector3d>& reference,
                                     const std::vector<Eigen::Vector3d>& other);

}  // namespace tissuemesh
