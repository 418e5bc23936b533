#include "solver_check/solution_comparison.h"

#include "core/errors.h"

#include <algorithm>
#include <limits>
#include <string>

namespace tissuemesh {

SolutionComparison compare_solutions(const std::vector<Eigen::Vector3d>& reference,
                                     const std::vector<Eigen::Vector3d>& other) {
  if (reference.size() != other.size())
    throw InputError("cannot compare displacement fields of " + std::to_string(reference.size()) + " and " +
                     std::to_string(other.size()) + " nodes");
  if (reference.empty()) throw InputError("cannot compare empty displacement fields");
  SolutionComparison c;
  double sum = 0.0;
  for (std::size_t i = 0; i < reference.size(); ++i) {
    if (!reference[i].allFinite() || !other[i].allFinite())
      throw InputError("cannot compare displacement fields: non-finite displacement at node " + std::to_string(i) +
                       " (0-based)");
    const double d = (other[i] - reference[i]).norm();
    sum += d;
    if (d > c.max_diff || c.max_diff_node < 0) {
      c.max_diff = d;
      c.max_diff_node = static_cast<int>(i);
    }
    c.max_u_reference = std::max(c.max_u_reference, reference[i].norm());
    c.max_u_other = std::max(c.max_u_other, other[i].norm());
  }
  c.mean_diff = sum / static_cast<double>(reference.size());
  if (c.max_u_reference > 0.0) {
    c.max_diff_rel = c.max_diff / c.max_u_reference;
    c.mean_diff_rel = c.mean_diff / c.max_u_reference;
  } else if (c.max_diff > 0.0) {
    c.max_diff_rel = c.mean_diff_rel = std::numeric_limits<double>::infinity();
  }
  return c;
}

}  // namespace tissuemesh
