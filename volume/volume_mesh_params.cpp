#include "volume/volume_mesh_params.h"

#include "core/errors.h"

namespace tissuemesh {

VolumeMeshParams VolumeMeshParams::from_yaml(YamlMap& m) {
  VolumeMeshParams p;
  p.mesher = m.text("mesher", p.mesher);
  if (p.mesher != "cgal" && p.mesher != "tetgen")
    throw InputError(m.where("mesher") + ": unknown mesher '" + p.mesher + "' (supported: cgal, tetgen)");
  const long long target = m.integer("target_tets", 0);
  if (target < 0 || target > 200000000)
    throw InputError(m.where("target_tets") + ": must be in 0..200000000 tets (0 = sizes as given), got " +
                     std::to_string(target));
  p.target_tets = static_cast<std::size_t>(target);
  p.surface_edge_factor = m.in_range("surface_edge_factor", p.surface_edge_factor, 0.1, 10.0);
  p.cell_edge_factor = m.in_range("cell_edge_factor", p.cell_edge_factor, 0.0, 100.0);
  if (p.mesher == "cgal" && p.cell_edge_factor < 0.1)
    throw InputError(m.where("cell_edge_factor") + ": must be in [0.1, 100] with volume.mesher: cgal (0, no size "
                     "bound, is TetGen's), got " + std::to_string(p.cell_edge_factor));
  p.cell_growth = m.in_range("cell_growth", p.cell_growth, 0.0, 100.0);
  p.max_cell_edge_mm = m.in_range("max_cell_edge_mm", p.max_cell_edge_mm, 0.0, 1e6);
  p.feature_angle_deg = m.in_range("feature_angle_deg", p.feature_angle_deg, 1.0, 180.0);
  // Bounds: CGAL's refinement is only proven to terminate for facet angle <= 30 degrees and
  // radius-edge ratio >= 2 (CGAL Mesh_3 manual).
  p.facet_angle_deg = m.in_range("facet_angle_deg", p.facet_angle_deg, 0.0, 30.0);
  p.facet_distance_mm = m.in_range("facet_distance_mm", p.facet_distance_mm, 0.0, 1e6);
  p.cell_radius_edge_ratio = m.in_range("cell_radius_edge_ratio", p.cell_radius_edge_ratio, 2.0, 100.0);
  p.optimise.read(m);
  if (p.mesher == "tetgen" && (p.cell_growth > 0.0 || p.max_cell_edge_mm > 0.0))
    throw InputError(m.where(p.cell_growth > 0.0 ? "cell_growth" : "max_cell_edge_mm") +
                     ": CGAL only; with volume.mesher: tetgen the interior follows the surface's sizes "
                     "(cell_edge_factor, or target_tets)");
  m.finish();
  return p;
}

void VolumeMeshParams::to_yaml(YAML::Emitter& out) const {
  out << YAML::BeginMap;
  out << YAML::Key << "mesher" << YAML::Value << mesher;
  out << YAML::Key << "target_tets" << YAML::Value << target_tets;
  out << YAML::Key << "surface_edge_factor" << YAML::Value << surface_edge_factor;
  out << YAML::Key << "cell_edge_factor" << YAML::Value << cell_edge_factor;
  out << YAML::Key << "cell_growth" << YAML::Value << cell_growth;
  out << YAML::Key << "max_cell_edge_mm" << YAML::Value << max_cell_edge_mm;
  out << YAML::Key << "feature_angle_deg" << YAML::Value << feature_angle_deg;
  out << YAML::Key << "facet_angle_deg" << YAML::Value << facet_angle_deg;
  out << YAML::Key << "facet_distance_mm" << YAML::Value << facet_distance_mm;
  out << YAML::Key << "cell_radius_edge_ratio" << YAML::Value << cell_radius_edge_ratio;
  optimise.emit(out);
  out << YAML::EndMap;
}

}  // namespace tissuemesh
