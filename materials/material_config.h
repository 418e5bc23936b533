// The `materials:` section of a config: tissue name -> MaterialSpec (core/material_spec.h).
//
//   materials:
//     preset: materials/ucl-niftysim-invivo.yaml   # optional; relative to this config file, else
//                                                  # to the shipped configs/ (source, installed);
//                                                  # its tissues, then the entries below override
//     fat:
//       law: neo-hookean        # neo-hookean | compressible-neo-hookean | mooney-rivlin | ogden
//       mu: 150 Pa              # parameters in ONE of the usual forms (quantities with units):
//       K: 50 kPa               #   E + nu | mu + K | mu + lambda | C10 + D1 | c1 + c2 + k
//       density: 1000 kg/m^3    #   (mooney-rivlin: c1 + c2 + k, or C10 + C01 + D1/K/nu)
//       source: "text"          # optional citation, copied into exported files and records
//     tumor:
//       law: ogden
//       terms: [{mu: 300 Pa, alpha: 2}, {mu: 10 Pa, alpha: -2}]   # 1-3 terms (Abaqus mu_i)
//       K: 100 kPa              # or D1, or nu (with mu = sum mu_i)
//       density: 1000 kg/m^3
//
// Validation (InputError naming file, key and reason): mu > 0, K > 0, -1 < nu < 0.5 (nu >= 0.5 is
// refused with the advice to give K), Ogden alpha_i != 0 and mu_i > 0, density in
// [100, 5000] kg/m^3 (anything else is almost always a unit mistake, e.g. t/mm^3 written as
// kg/m^3), an over- or under-determined parameter set, an unknown law or key.
#pragma once

#include "core/material_spec.h"
#include "core/yaml_map.h"

#include <yaml-cpp/yaml.h>

#include <map>
#include <string>

namespace tissuemesh {

struct MaterialTable {
  std::map<std::string, MaterialSpec> tissues;  ///< by tissue name
  std::string source = "<built-in defaults>";   ///< config (and preset) it came from
  std::string preset;                           ///< preset path as written, or empty

  /// Reads a `materials:` mapping. `config_path` resolves a relative preset path. Calls finish().
  static MaterialTable from_yaml(YamlMap& map, const std::string& config_path);
  /// The demo's materials: the UCL NiftySim in vivo set (configs/materials/ucl-niftysim-invivo.yaml)
  /// with an assumed tumour; identical to what configs/phantom.yaml loads (tested).
  static MaterialTable phantom_default();
  /// Effective materials, every parameter in its native form with units.
  void to_yaml(YAML::Emitter& out) const;
};

/// One material mapping (law, parameters, density, source); messages name it by the map's key path.
MaterialSpec parse_material(YamlMap& map);

}  // namespace tissuemesh
