// MeshConfig: the schema of a meshing config file (YAML), owned by code.
//
//   pipeline: direct            # 'direct' (CGAL from the image) or 'surface' (pipeline/surface_job.h:
//                               # multi-material surface, then CGAL from that surface)
//   tissues: [...]              # see core/tissue_table.h
//   ignore_labels: [0]
//   direct: {...}               # see volume/direct_mesh_params.h
//   surface: {...}              # see surface/surface_params.h
//   approach: {...}             # see surface/approach_params.h (pipeline: surface)
//   volume: {...}               # see volume/volume_mesh_params.h (pipeline: surface)
//   tetgen: {...}               # see volume/tetgen_params.h (check --tetgen)
//   checks: {...}               # see pipeline/mesh_checks.h (volume warnings)
//   phantom: {...}              # optional: the phantom `tissuemesh demo` generates (image/phantom.h)
//
// Unknown keys anywhere are errors naming the file and key path. `to_yaml()` prints the effective
// config (every key with its value, defaults filled in) for --print-config and the run record.
#pragma once

#include "core/tissue_table.h"
#include "volume/direct_mesh_params.h"
#include "image/phantom.h"
#include "pipeline/mesh_checks.h"
#include "surface/approach_params.h"
#include "surface/surface_params.h"
#include "volume/tetgen_params.h"
#include "volume/volume_mesh_params.h"

#include <string>

namespace tissuemesh {

struct MeshConfig {
  std::string source = "<built-in defaults>";  ///< file it came from (for messages)
  std::string pipeline = "direct";
  TissueTable tissues;
  DirectMeshParams direct;
  SurfaceParams surface;
  ApproachParams approach;
  VolumeMeshParams volume;
  TetgenParams tetgen;
  MeshChecks checks;
  PhantomParams phantom;

  /// Loads and validates a config file; throws InputError naming the file and key.
  static MeshConfig load(const std::string& path);
  /// Same from a parsed document; `source` names it in messages.
  static MeshConfig parse(const YAML::Node& root, const std::string& source);
  /// Reads the meshing keys of a whole-pipeline config's top level without finish(): the caller
  /// (app/job_config.h) reads the other sections and then rejects unknown keys.
  static MeshConfig from_top(YamlMap& top);
  /// The config `tissuemesh demo` uses when given none; identical to configs/phantom.yaml
  /// (a test keeps them in sync).
  static MeshConfig phantom_default();

  std::string to_yaml() const;
  /// The same keys into an open top-level map of `out`.
  void emit_keys(YAML::Emitter& out) const;
};

}  // namespace tissuemesh
