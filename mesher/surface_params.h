// Parameters of the surface pipeline (config section `surface:`, issue #5).
//
//   surface:
//     relaxation_iterations: 10   # Taubin lambda|mu pairs of the constrained relaxation (0 = voxel corners)
#pragma once

#include "core/yaml_map.h"

namespace tissuemesh {

struct SurfaceParams {
  int relaxation_iterations = 10;  ///< Taubin lambda|mu pairs (mesher/surface_extraction.h); 0 = none

  /// Reads the `surface:` map (unknown keys are errors; values range-checked with the key named).
  static SurfaceParams from_yaml(YamlMap& map);
  void to_yaml(YAML::Emitter& out) const;
};

}  // namespace tissuemesh
