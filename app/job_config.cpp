#include "app/job_config.h"

#include "core/errors.h"

namespace tissuemesh::app {

JobConfig JobConfig::load(const std::string& path) {
  JobConfig c;
  c.source = path;
  YamlMap top(load_yaml_file(path), "", path);
  for (const char* key : {"pipeline", "tissues", "ignore_labels", "direct", "phantom"})
    c.has_mesh = c.has_mesh || top.has(key);
  if (c.has_mesh) {
    c.mesh = MeshConfig::from_top(top);
  } else {  // `check --tetgen` on a model config: the TetGen keys alone
    YamlMap tetgen = top.map("tetgen");
    c.mesh.tetgen = TetgenParams::from_yaml(tetgen);
  }
  c.has_materials = top.has("materials");
  YamlMap materials = top.map("materials");
  c.materials = MaterialTable::from_yaml(materials, path);
  YamlMap model = top.map("model");
  c.model = ModelSettings::from_yaml(model);
  YamlMap exports = top.map("export");
  c.exports = ExportOptions::from_yaml(exports);
  YamlMap prone2supine = top.map("prone2supine");
  c.prone2supine = Prone2SupineSettings::from_yaml(prone2supine);
  top.finish();
  return c;
}

JobConfig JobConfig::phantom_default() {
  JobConfig c;
  c.source = "<built-in phantom config>";
  c.has_mesh = true;
  c.mesh = MeshConfig::phantom_default();
  c.materials = MaterialTable::phantom_default();
  c.has_materials = true;
  c.model = ModelSettings::phantom_default();
  return c;
}

std::string JobConfig::to_yaml() const {
  YAML::Emitter out;
  out.SetDoublePrecision(15);  // 1e-06, not 9.9999999999999995e-07; still exact for typed values
  out << YAML::BeginMap;
  if (has_mesh) {
    mesh.emit_keys(out);
  } else {
    out << YAML::Key << "tetgen" << YAML::Value;
    mesh.tetgen.to_yaml(out);
  }
  out << YAML::Key << "materials" << YAML::Value;
  materials.to_yaml(out);
  out << YAML::Key << "model" << YAML::Value;
  model.to_yaml(out);
  out << YAML::Key << "export" << YAML::Value;
  exports.to_yaml(out);
  out << YAML::Key << "prone2supine" << YAML::Value;
  prone2supine.to_yaml(out);
  out << YAML::EndMap;
  return std::string(out.c_str()) + "\n";
}

const MeshConfig& JobConfig::require_mesh() const {
  if (!has_mesh)
    throw InputError(source + ": has no meshing keys (`tissues:` mapping labels to tissues is required to mesh)");
  return mesh;
}

void JobConfig::check_materials_cover_tissues() const {
  if (!has_materials) throw InputError(source + ": has no `materials:` section (every tissue needs a material)");
  for (const std::string& name : require_mesh().tissues.names())
    if (!materials.tissues.count(name))
      throw InputError(materials.source + ": materials: tissue '" + name + "' has no material (add `materials: " +
                       name + ": {...}`)");
}

}  // namespace tissuemesh::app
