#include "surface/approach_params.h"

#include "core/errors.h"

#include <cmath>

namespace tissuemesh {

ApproachParams ApproachParams::from_yaml(YamlMap& m) {
  ApproachParams p;
  p.enabled = m.boolean("enabled", p.enabled);
  p.target_tissue = m.text("target_tissue", p.target_tissue);
  p.entry_tissue = m.text("entry_tissue", p.entry_tissue);
  if (m.has("entry")) {
    const YAML::Node entry = m.raw("entry");
    if (entry.IsScalar() && entry.as<std::string>() == "auto") {
      p.auto_entry = true;
    } else {
      bool ok = entry.IsSequence() && entry.size() == 3;
      for (std::size_t i = 0; ok && i < 3; ++i) {
        try {
          p.entry_mm[static_cast<Eigen::Index>(i)] = entry[i].as<double>();
        } catch (const YAML::Exception&) {
          ok = false;
        }
        ok = ok && std::isfinite(p.entry_mm[static_cast<Eigen::Index>(i)]);
      }
      if (!ok) throw InputError(m.where("entry") + ": expected 'auto' or [x, y, z] in LPS mm");
      p.auto_entry = false;
    }
  }
  p.corridor_radius_mm = m.positive("corridor_radius_mm", p.corridor_radius_mm);
  p.ratio = m.in_range("ratio", p.ratio, 1.0, 100.0);
  p.falloff_mm = m.positive("falloff_mm", p.falloff_mm);
  m.finish();
  return p;
}

void ApproachParams::to_yaml(YAML::Emitter& out) const {
  out << YAML::BeginMap;
  out << YAML::Key << "enabled" << YAML::Value << enabled;
  out << YAML::Key << "target_tissue" << YAML::Value << target_tissue;
  out << YAML::Key << "entry_tissue" << YAML::Value << entry_tissue;
  out << YAML::Key << "entry" << YAML::Value;
  if (auto_entry) {
    out << "auto";
  } else {
    out << YAML::Flow << YAML::BeginSeq << entry_mm.x() << entry_mm.y() << entry_mm.z() << YAML::EndSeq;
  }
  out << YAML::Key << "corridor_radius_mm" << YAML::Value << corridor_radius_mm;
  out << YAML::Key << "ratio" << YAML::Value << ratio;
  out << YAML::Key << "falloff_mm" << YAML::Value << falloff_mm;
  out << YAML::EndMap;
}

}  // namespace tissuemesh
