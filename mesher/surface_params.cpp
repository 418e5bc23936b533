#include "mesher/surface_params.h"

#include "core/errors.h"

namespace tissuemesh {

SurfaceParams SurfaceParams::from_yaml(YamlMap& m) {
  SurfaceParams p;
  p.relaxation_iterations = m.integer("relaxation_iterations", p.relaxation_iterations);
  if (p.relaxation_iterations < 0 || p.relaxation_iterations > 1000)
    throw InputError(m.where("relaxation_iterations") + ": must be in 0..1000, got " +
                     std::to_string(p.relaxation_iterations));
  m.finish();
  return p;
}

void SurfaceParams::to_yaml(YAML::Emitter& out) const {
  out << YAML::BeginMap;
  out << YAML::Key << "relaxation_iterations" << YAML::Value << relaxation_iterations;
  out << YAML::EndMap;
}

}  // namespace tissuemesh
