#include "pipeline/mesh_config.h"

#include "core/errors.h"

namespace tissuemesh {

MeshConfig MeshConfig::parse(const YAML::Node& root, const std::string& source) {
  YamlMap top(root, "", source);
  MeshConfig c = from_top(top);
  top.finish();
  return c;
}

MeshConfig MeshConfig::from_top(YamlMap& top) {
  MeshConfig c;
  c.source = top.source();
  c.pipeline = top.text("pipeline", c.pipeline);
  if (c.pipeline != "direct" && c.pipeline != "surface") {
    throw InputError(top.where("pipeline") + ": unknown pipeline '" + c.pipeline + "' (supported: direct, surface)");
  }
  c.tissues = TissueTable::from_config(top);
  YamlMap direct = top.map("direct");
  c.direct = DirectMeshParams::from_yaml(direct);
  YamlMap surface = top.map("surface");
  c.surface = SurfaceParams::from_yaml(surface);
  YamlMap approach = top.map("approach");
  c.approach = ApproachParams::from_yaml(approach);
  YamlMap volume = top.map("volume");
  c.volume = VolumeMeshParams::from_yaml(volume);
  YamlMap tetgen = top.map("tetgen");
  c.tetgen = TetgenParams::from_yaml(tetgen);
  if (c.approach.enabled && (c.pipeline != "surface" || !c.surface.remesh()))
    throw InputError(top.where("approach") +
                     ": approach grading needs pipeline: surface with surface.target_vertices or surface.target_edge_mm "
                     "(the direct pipeline grades with direct.refine_tissue)");
  YamlMap checks = top.map("checks");
  c.checks = MeshChecks::from_yaml(checks);
  YamlMap phantom = top.map("phantom");
  c.phantom = parse_phantom_params(phantom);
  phantom.finish();
  return c;
}

MeshConfig MeshConfig::load(const std::string& path) { return parse(load_yaml_file(path), path); }

MeshConfig MeshConfig::phantom_default() {
  MeshConfig c;
  c.source = "<built-in phantom config>";
  c.tissues = TissueTable({{"fat", 0, {kFat}},
                           {"fgt", 0, {kFgt}},
                           {"tumor", 0, {kTumor}},
                           {"skin", 0, {kSkin}},
                           {"muscle", 0, {kMuscle}}},
                          {kAir, kThorax}, c.source);
  return c;
}

std::string MeshConfig::to_yaml() const {
  YAML::Emitter out;
  out << YAML::BeginMap;
  emit_keys(out);
  out << YAML::EndMap;
  return std::string(out.c_str()) + "\n";
}

void MeshConfig::emit_keys(YAML::Emitter& out) const {
  out << YAML::Key << "pipeline" << YAML::Value << pipeline;
  tissues.to_yaml(out);
  out << YAML::Key << "direct" << YAML::Value;
  direct.to_yaml(out);
  out << YAML::Key << "surface" << YAML::Value;
  surface.to_yaml(out);
  out << YAML::Key << "approach" << YAML::Value;
  approach.to_yaml(out);
  out << YAML::Key << "volume" << YAML::Value;
  volume.to_yaml(out);
  out << YAML::Key << "tetgen" << YAML::Value;
  tetgen.to_yaml(out);
  out << YAML::Key << "checks" << YAML::Value;
  checks.to_yaml(out);
  out << YAML::Key << "phantom" << YAML::Value;
  phantom_params_to_yaml(phantom, out);
}

}  // namespace tissuemesh
