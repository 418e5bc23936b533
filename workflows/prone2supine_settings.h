// Prone2SupineSettings: the `prone2supine:` section of a config (docs/prone-to-supine.md). Owned by
// code: unknown keys are errors, to_yaml shows every key with its effective value.
//
//   prone2supine:
//     tolerance_mm: 0.01        # stop when the reference loaded prone again is this close to the
//                               #   input at every mesh node (largest nodal distance, mm)
//     max_iterations: 30        # forward prone solves of the fixed-point iteration (naive start included)
//     relaxation: {initial: 0.7, growth: 1.05, cut: 0.7}
//                               # alpha of X <- X - alpha (phi(X) - x_prone): x growth after an
//                               #   improvement (up to 1), x cut and a restart from the best
//                               #   iterate after a worsening or a failed solve
//     anderson_memory: 5        # Anderson acceleration of the updates (0: plain relaxation)
//     unloading:                # prone -> unloaded reference (the model's prone gravity)
//       constraints: {}         # node set -> fixed | sliding | free; sets not named keep model.node_sets'
//     supine:                   # unloaded reference -> supine
//       gravity: {direction: supine, acceleration: 9.81 m/s^2}   # or [x, y, z] LPS: a tilted table
//       constraints: {}         # e.g. {chest_wall: sliding}
#pragma once

#include "core/gravity_settings.h"
#include "core/yaml_map.h"

#include <map>
#include <string>

namespace tissuemesh {

/// What a node set does in one step of the workflow.
enum class StepConstraint { Fixed, Sliding, Free };

struct Prone2SupineSettings {
  double tolerance_mm = 0.01;
  int max_iterations = 30;
  double relaxation_initial = 0.7;  ///< alpha of the first update, in (0, 1]
  double relaxation_growth = 1.05;  ///< alpha *= growth after an improvement (capped at 1), >= 1
  double relaxation_cut = 0.7;      ///< alpha *= cut after a worsening, in (0, 1)
  int anderson_memory = 5;          ///< differences Anderson acceleration keeps, in [0, 50]; 0: plain relaxation
  /// Per node set name: its constraint in the unloading step (absent: as in model.node_sets).
  std::map<std::string, StepConstraint> unloading_constraints;
  GravitySettings supine_gravity = [] {
    GravitySettings g;
    g.direction = "supine";
    return g;
  }();
  std::map<std::string, StepConstraint> supine_constraints;  ///< same for the supine step

  /// Reads a `prone2supine:` mapping (absent keys keep the defaults) and calls map.finish();
  /// InputError naming the key for a wrong type, a value out of range or an unknown constraint.
  /// Set names are checked against the model later (prone_to_supine.h).
  static Prone2SupineSettings from_yaml(YamlMap& map);
  void to_yaml(YAML::Emitter& out) const;
};

/// "fixed", "sliding", "free".
const char* step_constraint_name(StepConstraint c);

}  // namespace tissuemesh
