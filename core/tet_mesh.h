// TetMesh: a multi-material linear tetrahedral mesh in physical millimetres (LPS).
//
// Contract: every tet (a,b,c,d) is positively oriented, i.e. (b-a).((c-a)x(d-a)) > 0;
// tissue_ids[t] in 1..tissue_names.size() names tissue_names[id-1]; 0 is "outside" and never
// appears on a tet. The mesher and readers guarantee it; `validate` checks it.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>  // cross()

#include <array>
#include <string>
#include <vector>

namespace tissuemesh {

struct TetMesh {
  std::vector<Eigen::Vector3d> points;         ///< node coordinates, LPS mm
  std::vector<std::array<int, 4>> tets;        ///< node indices (0-based), positively oriented
  std::vector<int> tissue_ids;                 ///< per tet, 1-based index into tissue_names
  std::vector<std::string> tissue_names;       ///< tissue id i -> tissue_names[i-1]

  std::size_t num_tissues() const { return tissue_names.size(); }

  /// Throws InputError naming `what` and the first offending tet when sizes disagree, an index is
  /// out of range, a coordinate is not finite or a tissue id is unknown. Orientation is checked by
  /// the quality report instead.
  void validate(const std::string& what) const;
};

/// Keeps the tets t with keep[t] != 0 (in order) and drops the nodes no kept tet uses, keeping
/// the order of the remaining nodes. keep.size() must equal mesh.tets.size().
void keep_tets(TetMesh& mesh, const std::vector<char>& keep);

/// Signed volume of the tetrahedron (a,b,c,d) in mm^3: positive when positively oriented.
inline double signed_tet_volume(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                const Eigen::Vector3d& c, const Eigen::Vector3d& d) {
  return (b - a).dot((c - a).cross(d - a)) / 6.0;
}

}  // namespace tissuemesh
