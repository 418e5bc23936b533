// TriSurface: a multi-material triangle surface, the surface pipeline's data
// (docs/surface-pipeline.md).
//
// Every boundary between two regions is stored once: triangle t separates region labels[t][0] = p
// from labels[t][1] = q with p < q, and its winding (right-hand rule) makes the normal point from p
// into q. Regions are tissue ids (1-based, as in TetMesh) and 0 = outside. The triangles bounding
// tissue i, those with p == i kept and those with q == i reversed, form its closed, outward-oriented
// boundary. Curves where three or more regions meet are explicit polylines (`junctions`): vertex
// index chains, closed when front() == back(); every junction edge is an edge of the triangles.
// Coordinates are physical LPS millimetres.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>  // cross()

#include <array>
#include <string>
#include <vector>

namespace tissuemesh {

struct TriSurface {
  std::vector<Eigen::Vector3d> points;           ///< LPS mm
  std::vector<std::array<int, 3>> triangles;     ///< vertex indices, normal from labels[t][0] into labels[t][1]
  std::vector<std::array<int, 2>> labels;        ///< per triangle {p, q}, p < q, 0 = outside
  std::vector<std::vector<int>> junctions;       ///< polylines where >= 3 regions meet
  std::vector<std::string> tissue_names;         ///< tissue id i -> tissue_names[i-1]

  /// Throws InputError naming `what` and the first offending triangle or polyline when sizes
  /// disagree, an index is out of range, a triangle is degenerate (repeated vertex), p >= q, a
  /// region id is unknown or a coordinate is not finite.
  void validate(const std::string& what) const;

  /// The closed boundary of tissue `id`, oriented outward: triangle indices into `triangles` and,
  /// per entry, whether its winding must be reversed (q == id).
  void tissue_boundary(int id, std::vector<int>& triangle_ids, std::vector<char>& reversed) const;
};

}  // namespace tissuemesh
