// Parameters of the TetGen backend (config section `tetgen:`; volume/tetgen_mesher.h), the
// cross-check mesher of `tissuemesh check --tetgen`.
#pragma once

#include "core/yaml_map.h"

#include <map>
#include <string>

namespace tissuemesh {

struct TetgenParams {
  /// Largest circumradius / shortest edge of a tet (TetGen's -q first value, > 1; 2 is the
  /// classical bound with guaranteed termination).
  double radius_edge_ratio = 2.0;
  /// Smallest dihedral angle TetGen aims for (-q second value, degrees; 0 = TetGen's default).
  double min_dihedral_deg = 0.0;
  /// `check --tetgen`: TetGen's largest circumradius at every surface node is the largest the
  /// checked mesh has there (quality/node_spacing.h), so both meshes have the same resolution and
  /// the comparison measures the mesher, not the mesh size. false: per-tissue volume bounds only.
  bool size_from_mesh = true;
  /// Maximum tet volume per tissue name, mm^3. Tissues not listed get no bound when sizes come
  /// from the mesh, else the volume of the regular tet whose edge is the mean edge length of the
  /// tissue's boundary triangles.
  std::map<std::string, double> max_volume_mm3;

  /// Reads the `tetgen:` map (unknown keys are errors; the backend range-checks the values and
  /// names the key).
  static TetgenParams from_yaml(YamlMap& map);
  void to_yaml(YAML::Emitter& out) const;
};

}  // namespace tissuemesh
