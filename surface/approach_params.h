// The surgical approach that grades the surface resolution (config section `approach:`;
// docs/configuration.md, "Surface pipeline").
//
//   approach:
//     enabled: false            # grade the resolution along the approach (default off)
//     target_tissue: tumor      # the tissue the approach leads to
//     entry_tissue: skin        # for entry: auto, the tissue whose outer surface (|outside) is entered
//     entry: auto               # 'auto' = the entry tissue's outer-surface point nearest the target's
//                               # centroid, or [x, y, z] in LPS mm
//     corridor_radius_mm: 10    # radius of the corridor from the entry to the target centroid, mm
//     ratio: 3                  # size away from the approach / size inside it (>= 1)
//     falloff_mm: 20            # distance over which the size grows back, mm
#pragma once

#include "core/yaml_map.h"

#include <Eigen/Core>

#include <string>

namespace tissuemesh {

struct ApproachParams {
  bool enabled = false;
  std::string target_tissue = "tumor";
  std::string entry_tissue = "skin";
  bool auto_entry = true;
  Eigen::Vector3d entry_mm = Eigen::Vector3d::Zero();  ///< LPS mm, when !auto_entry
  double corridor_radius_mm = 10.0;
  double ratio = 3.0;
  double falloff_mm = 20.0;

  /// Reads the `approach:` map (unknown keys are errors; values range-checked with the key named).
  static ApproachParams from_yaml(YamlMap& map);
  void to_yaml(YAML::Emitter& out) const;
};

}  // namespace tissuemesh
