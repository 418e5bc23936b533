// ModelSettings: the `model:` section of a config: what turns a mesh into a Model besides the
// materials (which materials/material_config.h reads). Owned by code; unknown keys are errors.
//
//   model:
//     units: mm-t-s               # SI | mm-t-s (MPa, t/mm^3) | mm-kg-s (kPa, kg/mm^3)
//     element: auto               # tet4 | tet10 (straight edges, midside nodes shared) | auto
//                                 #   (default): tet10 when a tissue has nu >= 0.49, else tet4
//     node_order: rcm             # rcm (default): reverse Cuthill-McKee, a small matrix profile
//                                 #   (FEBio's skyline solver without MKL); corners renumbered among
//                                 #   themselves, tet10 midside nodes after them, a tissue's
//                                 #   elements by lowest corner | mesh: keep the mesh's node and
//                                 #   element order (core/node_ordering.h)
//     node_sets:                  # each: a name, one selection, a constraint
//       - name: chest_wall
//         between: [muscle, outside]   # nodes on the interface between two sides; a side is a
//                                      # tissue name, a list of names, or `outside`
//         # plane: {point_mm: [0, 40, 0], normal: [0, 1, 0], tolerance_mm: 0.5}
//         # box_mm: [xmin, ymin, zmin, xmax, ymax, zmax]
//         constraint: fixed            # fixed (u = 0) | sliding (n . u = 0)
//     face_sets:
//       - {name: skin, between: [skin, outside]}   # same selections as node sets
//     gravity: {direction: prone, acceleration: 9.81 m/s^2}
//                                  # direction: prone (towards anterior, -y LPS) | supine (+y)
//                                  #   | none | [x, y, z] (LPS, normalised)
//     analysis: {load_steps: 10, ...} # see AnalysisSettings in core/model.h
#pragma once

#include "core/gravity_settings.h"
#include "core/model.h"
#include "core/yaml_map.h"

#include <yaml-cpp/yaml.h>

#include <Eigen/Core>

#include <optional>
#include <string>
#include <vector>

namespace tissuemesh {

/// One side of an interface: a set of tissue names; empty `tissues` with `outside` = the exterior.
struct InterfaceSide {
  std::vector<std::string> tissues;
  bool outside = false;
};

/// How a node or face set is chosen. Exactly one of the three selections is used.
struct SetSelection {
  enum class Kind { Between, Plane, Box } kind = Kind::Between;
  InterfaceSide side_a, side_b;                       ///< Between
  Eigen::Vector3d plane_point_mm = Eigen::Vector3d::Zero();   ///< Plane
  Eigen::Vector3d plane_normal = Eigen::Vector3d::UnitY();    ///< Plane (normalised)
  double plane_tolerance_mm = 0.5;                           ///< Plane
  Eigen::Vector3d box_min_mm = Eigen::Vector3d::Zero();      ///< Box
  Eigen::Vector3d box_max_mm = Eigen::Vector3d::Zero();      ///< Box
  std::string describe() const;  ///< "interface muscle|outside", "plane ...", "box ..."
};

struct NodeSetSettings {
  std::string name;
  SetSelection selection;
  Constraint constraint = Constraint::Fixed;
};

struct FaceSetSettings {
  std::string name;
  SetSelection selection;
};

/// How build_model numbers the nodes (core/model.h).
enum class NodeOrder { ReverseCuthillMcKee, Mesh };

struct ModelSettings {
  UnitSystem units = UnitSystem::MillimetreTonneSecond;
  /// tet4 | tet10; empty = `auto`: tet10 when a tissue of the mesh has Poisson's ratio >= 0.49
  /// (tet4 locks there, docs/solver.md "Elements"), else tet4 (default_element).
  std::optional<ElementOrder> element;
  NodeOrder node_order = NodeOrder::ReverseCuthillMcKee;  ///< `rcm` | `mesh`
  std::vector<NodeSetSettings> node_sets;
  std::vector<FaceSetSettings> face_sets;
  GravitySettings gravity;  ///< prone, 9.81 m/s^2 by default
  AnalysisSettings analysis;

  /// The settings `tissuemesh demo` uses: chest wall (muscle|outside) fixed, skin face set, prone
  /// gravity, mm-t-s, tet4 (explicitly, see the .cpp), RCM node order. Identical to the `model:`
  /// section of configs/phantom.yaml (tested).
  static ModelSettings phantom_default();
  /// Reads a `model:` mapping; calls map.finish(). Throws InputError naming the key.
  static ModelSettings from_yaml(YamlMap& map);
  void to_yaml(YAML::Emitter& out) const;
};

/// The element `auto` chooses for these tissue materials: tet10 when any has nu >= 0.49.
ElementOrder default_element(const std::vector<MaterialSpec>& materials);

}  // namespace tissuemesh
