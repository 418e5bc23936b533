#include "volume/direct_mesh_params.h"

#include "core/errors.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace tissuemesh {

DirectMeshParams DirectMeshParams::from_yaml(YamlMap& m) {
  DirectMeshParams p;
  // Bounds: CGAL's refinement is only proven to terminate for facet angle <= 30 degrees and
  // radius-edge ratio >= 2 (CGAL Mesh_3 manual).
  p.facet_angle_deg = m.in_range("facet_angle_deg", p.facet_angle_deg, 0.0, 30.0);
  p.facet_size_mm = m.positive("facet_size_mm", p.facet_size_mm);
  p.facet_distance_mm = m.positive("facet_distance_mm", p.facet_distance_mm);
  p.cell_radius_edge_ratio = m.in_range("cell_radius_edge_ratio", p.cell_radius_edge_ratio, 2.0, 100.0);
  p.cell_size_mm = m.positive("cell_size_mm", p.cell_size_mm);
  YamlMap per = m.map("cell_size_per_tissue_mm");
  for (const std::string& name : per.keys()) p.cell_size_per_tissue_mm[name] = per.positive(name, 1.0);
  per.finish();
  p.refine_tissue = m.text("refine_tissue", p.refine_tissue);
  p.refine_size_mm = m.positive("refine_size_mm", p.refine_size_mm);
  p.refine_radius_mm = m.positive("refine_radius_mm", p.refine_radius_mm);
  p.smooth_boundaries = m.boolean("smooth_boundaries", p.smooth_boundaries);
  p.smoothing_sigma_mm = m.in_range("smoothing_sigma_mm", p.smoothing_sigma_mm, 0.0, 100.0);
  p.min_component_voxels = m.integer("min_component_voxels", p.min_component_voxels);
  if (p.min_component_voxels < 0 || p.min_component_voxels > 1000000)
    throw InputError(m.where("min_component_voxels") + ": must be in 0..1000000 voxels (0 = off), got " +
                     std::to_string(p.min_component_voxels));
  p.min_component_mm3 = m.in_range("min_component_mm3", p.min_component_mm3, 0.0, 1e6);
  const long long target = m.integer("target_tets", 0);
  if (target < 0 || target > 200000000)
    throw InputError(m.where("target_tets") + ": must be in 0..200000000 tets (0 = fixed sizes), got " +
                     std::to_string(target));
  p.target_tets = static_cast<std::size_t>(target);
  p.thickness_edge_ratio = m.in_range("thickness_edge_ratio", p.thickness_edge_ratio, 0.1, 10.0);
  p.size_growth = m.in_range("size_growth", p.size_growth, 0.05, 10.0);
  p.facet_distance_ratio = m.in_range("facet_distance_ratio", p.facet_distance_ratio, 0.001, 1.0);
  p.min_edge_mm = m.in_range("min_edge_mm", p.min_edge_mm, 0.0, 1e3);
  p.fit_island_volumes_below_mm3 = m.in_range("fit_island_volumes_below_mm3", p.fit_island_volumes_below_mm3, 0.0, 1e9);
  p.restore_volumes = m.boolean("restore_volumes", p.restore_volumes);
  p.optimise.read(m);
  m.finish();
  return p;
}

std::size_t DirectMeshParams::absorb_below_voxels(double voxel_mm3) const {
  // n voxels have less than min_component_mm3 exactly when n < min_component_mm3 / voxel_mm3; the
  // relative slack keeps a volume that is a whole number of voxels from rounding up past it.
  const double by_volume = voxel_mm3 > 0 ? std::ceil(min_component_mm3 / voxel_mm3 * (1 - 1e-9)) : 0.0;
  return std::max(static_cast<std::size_t>(min_component_voxels), static_cast<std::size_t>(by_volume));
}

void DirectMeshParams::to_yaml(YAML::Emitter& out) const {
  out << YAML::BeginMap;
  out << YAML::Key << "facet_angle_deg" << YAML::Value << facet_angle_deg;
  out << YAML::Key << "facet_size_mm" << YAML::Value << facet_size_mm;
  out << YAML::Key << "facet_distance_mm" << YAML::Value << facet_distance_mm;
  out << YAML::Key << "cell_radius_edge_ratio" << YAML::Value << cell_radius_edge_ratio;
  out << YAML::Key << "cell_size_mm" << YAML::Value << cell_size_mm;
  out << YAML::Key << "cell_size_per_tissue_mm" << YAML::Value << YAML::Flow << YAML::BeginMap;
  for (const auto& [name, size] : cell_size_per_tissue_mm) out << YAML::Key << name << YAML::Value << size;
  out << YAML::EndMap;
  out << YAML::Key << "refine_tissue" << YAML::Value << refine_tissue;
  out << YAML::Key << "refine_size_mm" << YAML::Value << refine_size_mm;
  out << YAML::Key << "refine_radius_mm" << YAML::Value << refine_radius_mm;
  out << YAML::Key << "smooth_boundaries" << YAML::Value << smooth_boundaries;
  out << YAML::Key << "smoothing_sigma_mm" << YAML::Value << smoothing_sigma_mm;
  out << YAML::Key << "min_component_voxels" << YAML::Value << min_component_voxels;
  out << YAML::Key << "min_component_mm3" << YAML::Value << min_component_mm3;
  out << YAML::Key << "target_tets" << YAML::Value << target_tets;
  out << YAML::Key << "thickness_edge_ratio" << YAML::Value << thickness_edge_ratio;
  out << YAML::Key << "size_growth" << YAML::Value << size_growth;
  out << YAML::Key << "facet_distance_ratio" << YAML::Value << facet_distance_ratio;
  out << YAML::Key << "min_edge_mm" << YAML::Value << min_edge_mm;
  out << YAML::Key << "fit_island_volumes_below_mm3" << YAML::Value << fit_island_volumes_below_mm3;
  out << YAML::Key << "restore_volumes" << YAML::Value << restore_volumes;
  optimise.emit(out);
  out << YAML::EndMap;
}

}  // namespace tissuemesh
