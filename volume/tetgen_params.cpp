#include "volume/tetgen_params.h"

namespace tissuemesh {

TetgenParams TetgenParams::from_yaml(YamlMap& m) {
  TetgenParams p;
  p.radius_edge_ratio = m.number("radius_edge_ratio", p.radius_edge_ratio);
  p.min_dihedral_deg = m.number("min_dihedral_deg", p.min_dihedral_deg);
  p.size_from_mesh = m.boolean("size_from_mesh", p.size_from_mesh);
  YamlMap per = m.map("max_volume_mm3");
  for (const std::string& name : per.keys()) p.max_volume_mm3[name] = per.number(name, 1.0);
  per.finish();
  m.finish();
  return p;
}

void TetgenParams::to_yaml(YAML::Emitter& out) const {
  out << YAML::BeginMap;
  out << YAML::Key << "radius_edge_ratio" << YAML::Value << radius_edge_ratio;
  out << YAML::Key << "min_dihedral_deg" << YAML::Value << min_dihedral_deg;
  out << YAML::Key << "size_from_mesh" << YAML::Value << size_from_mesh;
  out << YAML::Key << "max_volume_mm3" << YAML::Value << YAML::Flow << YAML::BeginMap;
  for (const auto& [name, v] : max_volume_mm3) out << YAML::Key << name << YAML::Value << v;
  out << YAML::EndMap;
  out << YAML::EndMap;
}

}  // namespace tissuemesh
