#include "surface/approach_field.h"

#include "core/errors.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <set>

namespace tissuemesh {
namespace {

int tissue_id(const TriSurface& s, const std::string& name, const std::string& key) {
  for (std::size_t i = 0; i < s.tissue_names.size(); ++i)
    if (s.tissue_names[i] == name) return static_cast<int>(i) + 1;
  throw InputError("approach." + key + ": unknown tissue '" + name + "'");
}

double segment_distance(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  const Eigen::Vector3d ab = b - a;
  const double len2 = ab.squaredNorm();
  const double t = len2 > 0.0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return (p - (a + t * ab)).norm();
}

}  // namespace

ApproachField::ApproachField(const TriSurface& s, const ApproachParams& params) : params_(params) {
  const int target = tissue_id(s, params.target_tissue, "target_tissue");
  // Area centroid of the target's boundary, and the radius holding all its boundary vertices.
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  double area = 0.0;
  std::set<int> vertices;
  for (std::size_t t = 0; t < s.triangles.size(); ++t) {
    if (s.labels[t][0] != target && s.labels[t][1] != target) continue;
    const Eigen::Vector3d &a = s.points[s.triangles[t][0]], &b = s.points[s.triangles[t][1]],
                          &c = s.points[s.triangles[t][2]];
    const double at = 0.5 * (b - a).cross(c - a).norm();
    sum += at * (a + b + c) / 3.0;
    area += at;
    vertices.insert(s.triangles[t].begin(), s.triangles[t].end());
  }
  if (!(area > 0.0)) throw InputError("approach.target_tissue: tissue '" + params.target_tissue + "' has no boundary");
  centroid_ = sum / area;
  for (int v : vertices) radius_ = std::max(radius_, (s.points[v] - centroid_).norm());
  if (!params.auto_entry) {
    entry_ = params.entry_mm;
    return;
  }
  const int entry = tissue_id(s, params.entry_tissue, "entry_tissue");
  double best = INFINITY;
  for (std::size_t t = 0; t < s.triangles.size(); ++t) {
    if (s.labels[t] != std::array<int, 2>{0, entry}) continue;
    for (int v : s.triangles[t]) {
      const double d = (s.points[v] - centroid_).norm();
      if (d < best || (d == best && v < 0)) {
        best = d;
        entry_ = s.points[v];
      }
    }
  }
  if (!std::isfinite(best))
    throw InputError("approach.entry_tissue: tissue '" + params.entry_tissue + "' has no outer surface (|outside)");
}

double ApproachField::focus_distance(const Eigen::Vector3d& p) const {
  const double to_target = std::max(0.0, (p - centroid_).norm() - radius_);
  const double to_corridor = std::max(0.0, segment_distance(p, entry_, centroid_) - params_.corridor_radius_mm);
  return std::min(to_target, to_corridor);
}

double ApproachField::relative_size(const Eigen::Vector3d& p) const {
  const double t = std::min(1.0, focus_distance(p) / params_.falloff_mm);
  const double smooth = t * t * (3.0 - 2.0 * t);
  const double inner = 1.0 / params_.ratio;
  return inner + (1.0 - inner) * smooth;
}

ApproachGrading measure_grading(const TriSurface& s, const ApproachField& field) {
  ApproachGrading g;
  std::set<std::pair<int, int>> seen;
  for (const auto& tri : s.triangles)
    for (int i = 0; i < 3; ++i) {
      const int a = std::min(tri[i], tri[(i + 1) % 3]), b = std::max(tri[i], tri[(i + 1) % 3]);
      if (!seen.insert({a, b}).second) continue;
      const double d = field.focus_distance(0.5 * (s.points[a] + s.points[b]));
      const double len = (s.points[a] - s.points[b]).norm();
      if (d <= 0.0) {
        g.inside_mean_edge_mm += len;
        ++g.inside_edges;
      } else if (d >= field.params().falloff_mm) {
        g.outside_mean_edge_mm += len;
        ++g.outside_edges;
      }
    }
  if (g.inside_edges) g.inside_mean_edge_mm /= static_cast<double>(g.inside_edges);
  if (g.outside_edges) g.outside_mean_edge_mm /= static_cast<double>(g.outside_edges);
  return g;
}

}  // namespace tissuemesh
