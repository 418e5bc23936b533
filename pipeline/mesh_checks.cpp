#include "pipeline/mesh_checks.h"

#include "core/errors.h"

#include <cmath>
#include <cstdio>

namespace tissuemesh {

MeshChecks MeshChecks::from_yaml(YamlMap& m) {
  MeshChecks c;
  c.volume_tolerance_percent = m.number("volume_tolerance_percent", c.volume_tolerance_percent);
  if (!(c.volume_tolerance_percent > 0) || !std::isfinite(c.volume_tolerance_percent))
    throw InputError(m.where("volume_tolerance_percent") + ": must be a positive number of percent");
  m.finish();
  return c;
}

void MeshChecks::to_yaml(YAML::Emitter& out) const {
  out << YAML::BeginMap;
  out << YAML::Key << "volume_tolerance_percent" << YAML::Value << volume_tolerance_percent;
  out << YAML::EndMap;
}

std::vector<VolumeDeviation> volume_deviations(const QualityReport& quality, const MeshChecks& checks) {
  std::vector<VolumeDeviation> out;
  for (const TissueQuality& t : quality.tissues) {
    if (!std::isfinite(t.volume_error_rel)) continue;
    const double percent = 100.0 * t.volume_error_rel;
    if (std::abs(percent) > checks.volume_tolerance_percent)
      out.push_back({t.name, t.volume_mm3, t.reference_volume_mm3, percent});
  }
  return out;
}

std::vector<std::string> volume_warnings(const std::vector<VolumeDeviation>& deviations,
                                         const MeshChecks& checks) {
  std::vector<std::string> out;
  for (const VolumeDeviation& d : deviations) {
    char buf[256];
    std::snprintf(buf, sizeof buf,
                  "tissue '%s': meshed volume %.1f mm^3 is %+.1f %% off its voxel volume %.1f mm^3 "
                  "(checks.volume_tolerance_percent: %g)",
                  d.tissue.c_str(), d.volume_mm3, d.error_percent, d.reference_volume_mm3,
                  checks.volume_tolerance_percent);
    out.emplace_back(buf);
  }
  return out;
}

}  // namespace tissuemesh
