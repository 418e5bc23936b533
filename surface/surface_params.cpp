#include "surface/surface_params.h"

#include "core/errors.h"

#include <cmath>

namespace tissuemesh {

SurfaceParams SurfaceParams::from_yaml(YamlMap& m) {
  SurfaceParams p;
  p.min_island_voxels = m.integer("min_island_voxels", p.min_island_voxels);
  if (p.min_island_voxels < 1 || p.min_island_voxels > 1000000)
    throw InputError(m.where("min_island_voxels") + ": must be in 1..1000000 voxels (1 = keep every component), got " +
                     std::to_string(p.min_island_voxels));
  p.relaxation_iterations = m.integer("relaxation_iterations", p.relaxation_iterations);
  if (p.relaxation_iterations < 0 || p.relaxation_iterations > 1000)
    throw InputError(m.where("relaxation_iterations") + ": must be in 0..1000, got " +
                     std::to_string(p.relaxation_iterations));
  p.target_vertices = m.integer("target_vertices", p.target_vertices);
  if (p.target_vertices < 0 || p.target_vertices > 50000000)
    throw InputError(m.where("target_vertices") + ": must be in 0..50000000 (0 = no remeshing), got " +
                     std::to_string(p.target_vertices));
  p.target_edge_mm = m.number("target_edge_mm", p.target_edge_mm);
  if (!(p.target_edge_mm >= 0.0) || !std::isfinite(p.target_edge_mm))
    throw InputError(m.where("target_edge_mm") + ": must be a length >= 0 mm (0 = use target_vertices), got " +
                     std::to_string(p.target_edge_mm));
  p.remesh_iterations = m.integer("remesh_iterations", p.remesh_iterations);
  if (p.remesh_iterations < 1 || p.remesh_iterations > 100)
    throw InputError(m.where("remesh_iterations") + ": must be in 1..100, got " + std::to_string(p.remesh_iterations));
  p.restore_volumes = m.boolean("restore_volumes", p.restore_volumes);
  p.thickness_edge_ratio = m.number("thickness_edge_ratio", p.thickness_edge_ratio);
  if (!(p.thickness_edge_ratio >= 0.0 && p.thickness_edge_ratio <= 10.0))
    throw InputError(m.where("thickness_edge_ratio") + ": must be in [0, 10] (edge length per mm of local thickness; 0 = off), got " +
                     std::to_string(p.thickness_edge_ratio));
  p.mean_quality_passes = m.integer("mean_quality_passes", p.mean_quality_passes);
  if (p.mean_quality_passes < 0 || p.mean_quality_passes > 20)
    throw InputError(m.where("mean_quality_passes") + ": must be in 0..20 (0 = none), got " +
                     std::to_string(p.mean_quality_passes));
  m.finish();
  return p;
}

void SurfaceParams::to_yaml(YAML::Emitter& out) const {
  out << YAML::BeginMap;
  out << YAML::Key << "min_island_voxels" << YAML::Value << min_island_voxels;
  out << YAML::Key << "relaxation_iterations" << YAML::Value << relaxation_iterations;
  out << YAML::Key << "target_vertices" << YAML::Value << target_vertices;
  out << YAML::Key << "target_edge_mm" << YAML::Value << target_edge_mm;
  out << YAML::Key << "remesh_iterations" << YAML::Value << remesh_iterations;
  out << YAML::Key << "restore_volumes" << YAML::Value << restore_volumes;
  out << YAML::Key << "thickness_edge_ratio" << YAML::Value << thickness_edge_ratio;
  out << YAML::Key << "mean_quality_passes" << YAML::Value << mean_quality_passes;
  out << YAML::EndMap;
}

}  // namespace tissuemesh
