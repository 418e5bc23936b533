// SweepSpec: a sweep file (`tissuemesh sweep --sweep SWEEP.yaml`; docs/sweeps.md). Owned by code:
// unknown keys are errors, to_yaml shows every key with its effective value.
//
//   parameters:                       # by config path, in this order (the columns of results.csv)
//     materials.fat.mu: {range: [100 Pa, 1 kPa], scale: log}     # scale: linear (default) | log
//     materials.tumor.E: {values: [3 kPa, 10 kPa, 30 kPa]}
//     materials.fgt.mu: {ratio_to: materials.fat.mu, range: [1, 4]}   # tied: its ratio to the other
//                                                                      #   is the design's dimension
//     model.gravity.acceleration: {range: [9.81 m/s^2, 19.62 m/s^2]}
//   design: {type: lhs, samples: 32, seed: 1}
//     # grid: {type: grid, levels: 3}   (levels per range; a values list gives its own)
//     # sobol: {type: sobol, samples: 64, seed: 1}   (base N of Saltelli's design: N (d + 2) solves)
//     # table: {type: table, file: samples.csv}      (header: the parameters' paths; SI values, ratios)
//   analysis: solve                   # the per-sample analysis: solve (the model under its gravity)
//                                     #   | prone2supine (the config's prone2supine: section; the
//                                     #   outputs are then the prone-to-supine displacements)
//   save_fields: false                # each sample's solution.vtu
//   export: []                        # each sample's models: febio, abaqus, sofa
//
// Paths: materials.<tissue>.<mu | K | E | nu | C10 | C01 | density> and
// model.gravity.acceleration (workflows/sweep_parameters.h says what each changes). Values are
// quantities with units (Pa, kPa, MPa; kg/m^3; m/s^2); nu and ratios are plain numbers.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace tissuemesh {

enum class ParameterScale { Linear, Log };

struct SweepParameter {
  std::string path;
  bool has_range = false;
  double lo = 0.0, hi = 0.0;  ///< range (SI; a ratio for a tied parameter)
  ParameterScale scale = ParameterScale::Linear;
  std::vector<double> values;  ///< a list instead of a range (SI; ratios for a tied parameter)
  std::string ratio_to;        ///< tied: value = ratio x the value of this parameter (empty: free)
};

enum class DesignType { Grid, Lhs, Sobol, Table };

struct SweepSpec {
  std::vector<SweepParameter> parameters;
  DesignType design = DesignType::Lhs;
  int levels = 3;              ///< grid: points per range
  int samples = 16;            ///< lhs: samples; sobol: base N
  std::uint64_t seed = 1;      ///< lhs, sobol
  std::string table_file;      ///< table: CSV path (relative to the sweep file)
  std::string analysis = "solve";
  bool save_fields = false;
  std::vector<std::string> exports;  ///< febio, abaqus, sofa
  std::string source;          ///< the sweep file

  /// Reads and checks a sweep file. InputError naming the file and key: unknown keys, an empty
  /// parameter list, a range with min > max or non-positive bounds on a log scale, a value without
  /// a unit where one is needed, both or neither of range and values, a tie to a parameter the
  /// file does not have or to a tied one, a duplicate path, an unknown design or export format.
  /// Paths are checked against the model later (sweep_parameters.h).
  static SweepSpec load(const std::string& path);
  std::string to_yaml() const;
};

const char* design_name(DesignType d);

}  // namespace tissuemesh
