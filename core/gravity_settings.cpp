#include "core/gravity_settings.h"

#include "core/errors.h"
#include "core/quantity.h"

namespace tissuemesh {

GravitySettings GravitySettings::from_yaml(YamlMap& map, const GravitySettings& defaults) {
  GravitySettings g = defaults;
  if (map.has("direction")) {
    YAML::Node dir = map.raw("direction");
    if (dir.IsSequence()) {
      const Eigen::Vector3d v = map.vector3("direction", Eigen::Vector3d::Zero());
      if (!(v.norm() > 0)) throw InputError(map.where("direction") + ": must not be the zero vector");
      g.direction = "vector";
      g.vector = v.normalized();
    } else {
      g.direction = dir.Scalar();
      if (g.direction != "prone" && g.direction != "supine" && g.direction != "none")
        throw InputError(map.where("direction") + ": unknown direction '" + g.direction +
                         "' (prone: towards anterior, supine: towards posterior, none, or [x, y, z] in LPS)");
    }
  }
  if (map.has("acceleration")) {
    g.m_s2 = parse_quantity(map.text("acceleration", ""), Dimension::Acceleration, map.where("acceleration"));
    if (!(g.m_s2 >= 0.0 && g.m_s2 <= 100.0))
      throw InputError(map.where("acceleration") + ": " + std::to_string(g.m_s2) +
                       " m/s^2 is outside [0, 100] m/s^2 (Earth: 9.81 m/s^2; check the unit)");
  }
  map.finish();
  return g;
}

void GravitySettings::to_yaml(YAML::Emitter& out) const {
  out << YAML::Flow << YAML::BeginMap << YAML::Key << "direction" << YAML::Value;
  if (direction == "vector")
    out << YAML::Flow << YAML::BeginSeq << vector[0] << vector[1] << vector[2] << YAML::EndSeq;
  else
    out << direction;
  out << YAML::Key << "acceleration" << YAML::Value << format_quantity(m_s2, Dimension::Acceleration)
      << YAML::EndMap;
}

Eigen::Vector3d GravitySettings::acceleration() const {
  // LPS: +y is posterior. Prone (face down): gravity pulls towards anterior = -y.
  if (direction == "prone") return {0.0, -m_s2, 0.0};
  if (direction == "supine") return {0.0, m_s2, 0.0};
  if (direction == "none") return Eigen::Vector3d::Zero();
  return m_s2 * vector;
}

}  // namespace tissuemesh
