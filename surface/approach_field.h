// ApproachField: the relative size field of an approach-graded surface (the approach-guided
// resolution of Alqaoud et al., "Multi-material, approach-guided, controlled-resolution breast
// meshing"; docs/surface-pipeline.md, "3. Approach grading").
//
// The focus is the target tissue (approximated by the ball around its boundary's area centroid
// that holds all its boundary vertices) and the corridor (the points within corridor_radius of the
// segment from the entry point to that centroid). At focus distance d (0 inside the focus)
//   s(d) = 1/ratio + (1 - 1/ratio) * smoothstep(d / falloff),  smoothstep(t) = 3t^2 - 2t^3 on [0, 1],
// so the size is ratio times smaller inside the focus and grows back smoothly (C1) to 1.
// `entry: auto` takes the vertex of the entry tissue's outer surface (entry|outside triangles)
// nearest the centroid.
#pragma once

#include "core/tri_surface.h"
#include "surface/approach_params.h"

#include <Eigen/Core>

namespace tissuemesh {

class ApproachField {
 public:
  /// Throws InputError when a named tissue is unknown or has no boundary in `surface`.
  ApproachField(const TriSurface& surface, const ApproachParams& params);

  double focus_distance(const Eigen::Vector3d& p) const;  ///< mm, 0 inside the focus
  double relative_size(const Eigen::Vector3d& p) const;   ///< s in [1/ratio, 1]

  const Eigen::Vector3d& entry() const { return entry_; }
  const Eigen::Vector3d& target_centroid() const { return centroid_; }
  double target_radius_mm() const { return radius_; }
  const ApproachParams& params() const { return params_; }

 private:
  ApproachParams params_;
  Eigen::Vector3d entry_, centroid_;
  double radius_ = 0.0;
};

/// Mean edge length (mm) of `surface` inside the focus (edge midpoint at focus distance 0) and
/// beyond the falloff (distance >= falloff), and their ratio (inside / beyond).
struct ApproachGrading {
  double inside_mean_edge_mm = 0.0;
  double outside_mean_edge_mm = 0.0;
  std::size_t inside_edges = 0, outside_edges = 0;
  double ratio() const { return outside_mean_edge_mm > 0.0 ? inside_mean_edge_mm / outside_mean_edge_mm : 0.0; }
};
ApproachGrading measure_grading(const TriSurface& surface, const ApproachField& field);

}  // namespace tissuemesh
