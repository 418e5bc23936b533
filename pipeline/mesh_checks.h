// What a mesh run checks and warns about after meshing (config section `checks:`), and the
// per-tissue volume warnings it produces.
//
//   checks:
//     volume_tolerance_percent: 5   # a tissue whose meshed volume differs from its voxel volume
//                                   # by more than this is a named warning in the report
#pragma once

#include "core/yaml_map.h"
#include "quality/mesh_quality.h"

#include <string>
#include <vector>

namespace tissuemesh {

struct MeshChecks {
  /// Largest |meshed - voxel volume| / voxel volume of a tissue without a warning, percent (> 0).
  double volume_tolerance_percent = 5.0;

  /// Reads the `checks:` map; throws InputError naming the key for an unknown key or a value <= 0.
  static MeshChecks from_yaml(YamlMap& map);
  void to_yaml(YAML::Emitter& out) const;
};

/// One tissue outside the volume tolerance.
struct VolumeDeviation {
  std::string tissue;
  double volume_mm3 = 0;            ///< meshed
  double reference_volume_mm3 = 0;  ///< voxel volume
  double error_percent = 0;         ///< 100 (volume - reference) / reference
};

/// The tissues of `quality` (not its total) whose volume error exceeds the tolerance, in tissue
/// order; tissues without a reference volume are skipped.
std::vector<VolumeDeviation> volume_deviations(const QualityReport& quality, const MeshChecks& checks);

/// "tissue 'skin': meshed volume 3,297.1 mm^3 is -61.0 % of its voxel volume 8,452.0 mm^3
/// (tolerance 5 %)", one per deviation.
std::vector<std::string> volume_warnings(const std::vector<VolumeDeviation>& deviations,
                                         const MeshChecks& checks);

}  // namespace tissuemesh
