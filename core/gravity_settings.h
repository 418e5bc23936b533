// GravitySettings: a `gravity:` mapping of a config (the model's, and each prone-to-supine step's).
//
//   gravity: {direction: prone, acceleration: 9.81 m/s^2}
//     direction: prone (towards anterior, -y LPS) | supine (towards posterior, +y) | none
//                | [x, y, z] (LPS, normalised; a tilted table)
//     acceleration: a quantity with an acceleration unit, in [0, 100] m/s^2
#pragma once

#include "core/yaml_map.h"

#include <Eigen/Core>

#include <string>

namespace tissuemesh {

struct GravitySettings {
  std::string direction = "prone";                     ///< prone | supine | none | vector
  Eigen::Vector3d vector = Eigen::Vector3d::Zero();    ///< when "vector" (unit length)
  double m_s2 = 9.81;                                  ///< magnitude, m/s^2

  /// Reads a `gravity:` mapping (keys absent keep `defaults`' values) and calls map.finish().
  /// InputError naming the key: an unknown direction, a zero vector, an acceleration outside
  /// [0, 100] m/s^2 or without an acceleration unit.
  static GravitySettings from_yaml(YamlMap& map, const GravitySettings& defaults);
  /// As a flow mapping {direction: ..., acceleration: ...}.
  void to_yaml(YAML::Emitter& out) const;
  /// The acceleration vector in m/s^2, LPS.
  Eigen::Vector3d acceleration() const;
};

}  // namespace tissuemesh
