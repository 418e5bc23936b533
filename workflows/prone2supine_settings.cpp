#include "workflows/prone2supine_settings.h"

#include "core/errors.h"

namespace tissuemesh {

namespace {

std::map<std::string, StepConstraint> read_constraints(YamlMap& step) {
  std::map<std::string, StepConstraint> out;
  YamlMap constraints = step.map("constraints");
  for (const std::string& set : constraints.keys()) {
    const std::string value = constraints.text(set, "");
    if (value == "fixed")
      out[set] = StepConstraint::Fixed;
    else if (value == "sliding")
      out[set] = StepConstraint::Sliding;
    else if (value == "free")
      out[set] = StepConstraint::Free;
    else
      throw InputError(constraints.where(set) + ": unknown constraint '" + value + "' (fixed, sliding or free)");
  }
  constraints.finish();
  return out;
}

void emit_constraints(YAML::Emitter& out, const std::map<std::string, StepConstraint>& constraints) {
  out << YAML::Key << "constraints" << YAML::Value << YAML::Flow << YAML::BeginMap;
  for (const auto& [set, c] : constraints) out << YAML::Key << set << YAML::Value << step_constraint_name(c);
  out << YAML::EndMap;
}

}  // namespace

const char* step_constraint_name(StepConstraint c) {
  switch (c) {
    case StepConstraint::Fixed: return "fixed";
    case StepConstraint::Sliding: return "sliding";
    case StepConstraint::Free: return "free";
  }
  return "?";
}

Prone2SupineSettings Prone2SupineSettings::from_yaml(YamlMap& map) {
  Prone2SupineSettings s;
  s.tolerance_mm = map.in_range("tolerance_mm", s.tolerance_mm, 1e-9, 100.0);
  s.max_iterations = map.integer("max_iterations", s.max_iterations);
  if (s.max_iterations < 1 || s.max_iterations > 1000)
    throw InputError(map.where("max_iterations") + ": must be in [1, 1000], got " + std::to_string(s.max_iterations));
  YamlMap relaxation = map.map("relaxation");
  s.relaxation_initial = relaxation.in_range("initial", s.relaxation_initial, 1e-3, 1.0);
  s.relaxation_growth = relaxation.in_range("growth", s.relaxation_growth, 1.0, 10.0);
  s.relaxation_cut = relaxation.in_range("cut", s.relaxation_cut, 0.01, 0.99);
  relaxation.finish();
  s.anderson_memory = map.integer("anderson_memory", s.anderson_memory);
  if (s.anderson_memory < 0 || s.anderson_memory > 50)
    throw InputError(map.where("anderson_memory") + ": must be in [0, 50], got " + std::to_string(s.anderson_memory));
  YamlMap unloading = map.map("unloading");
  s.unloading_constraints = read_constraints(unloading);
  unloading.finish();
  YamlMap supine = map.map("supine");
  YamlMap gravity = supine.map("gravity");
  s.supine_gravity = GravitySettings::from_yaml(gravity, s.supine_gravity);
  s.supine_constraints = read_constraints(supine);
  supine.finish();
  map.finish();
  return s;
}

void Prone2SupineSettings::to_yaml(YAML::Emitter& out) const {
  out << YAML::BeginMap;
  out << YAML::Key << "tolerance_mm" << YAML::Value << tolerance_mm;
  out << YAML::Key << "max_iterations" << YAML::Value << max_iterations;
  out << YAML::Key << "relaxation" << YAML::Value << YAML::Flow << YAML::BeginMap << YAML::Key << "initial"
      << YAML::Value << relaxation_initial << YAML::Key << "growth" << YAML::Value << relaxation_growth
      << YAML::Key << "cut" << YAML::Value << relaxation_cut << YAML::EndMap;
  out << YAML::Key << "anderson_memory" << YAML::Value << anderson_memory;
  out << YAML::Key << "unloading" << YAML::Value << YAML::BeginMap;
  emit_constraints(out, unloading_constraints);
  out << YAML::EndMap;
  out << YAML::Key << "supine" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "gravity" << YAML::Value;
  supine_gravity.to_yaml(out);
  emit_constraints(out, supine_constraints);
  out << YAML::EndMap;
  out << YAML::EndMap;
}

}  // namespace tissuemesh
