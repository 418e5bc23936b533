#include "fe_export/export_options.h"

#include "core/errors.h"

namespace tissuemesh {

ExportOptions ExportOptions::from_yaml(YamlMap& map) {
  ExportOptions o;
  if (map.has("formats")) {
    YAML::Node list = map.raw("formats");
    if (!list.IsSequence() || list.size() == 0)
      throw InputError(map.where("formats") + ": expected a non-empty list, e.g. [febio, abaqus]");
    o.formats.clear();
    for (const YAML::Node& n : list) o.formats.push_back(n.Scalar());
  }
  YamlMap abaqus = map.map("abaqus");
  o.abaqus.hybrid = abaqus.boolean("hybrid", o.abaqus.hybrid);
  abaqus.finish();
  YamlMap febio = map.map("febio");
  o.febio.linear_solver = febio.text("linear_solver", o.febio.linear_solver);
  febio.finish();
  YamlMap sofa = map.map("sofa");
  o.sofa.version = sofa.text("version", o.sofa.version);
  if (o.sofa.version != "24.06" && o.sofa.version != "25.06")
    throw InputError(sofa.where("version") + ": unknown SOFA scene layout '" + o.sofa.version +
                     "' (24.06: SOFA v24.06-v24.12; 25.06: v25.06 and later)");
  sofa.finish();
  map.finish();
  return o;
}

void ExportOptions::to_yaml(YAML::Emitter& out) const {
  out << YAML::BeginMap;
  out << YAML::Key << "formats" << YAML::Value << YAML::Flow << formats;
  out << YAML::Key << "abaqus" << YAML::Value << YAML::Flow << YAML::BeginMap << YAML::Key << "hybrid"
      << YAML::Value << abaqus.hybrid << YAML::EndMap;
  out << YAML::Key << "febio" << YAML::Value << YAML::Flow << YAML::BeginMap << YAML::Key << "linear_solver"
      << YAML::Value << febio.linear_solver << YAML::EndMap;
  out << YAML::Key << "sofa" << YAML::Value << YAML::Flow << YAML::BeginMap << YAML::Key << "version"
      << YAML::Value << sofa.version << YAML::EndMap;
  out << YAML::EndMap;
}

}  // namespace tissuemesh
