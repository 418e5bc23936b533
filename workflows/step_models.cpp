#include "workflows/step_models.h"

#include "core/errors.h"

#include <map>
#include <string>

namespace tissuemesh {

namespace {

using Constraints = std::map<std::string, StepConstraint>;

void check_names(const ModelSettings& settings, const Constraints& step, const std::string& where) {
  for (const auto& [name, c] : step) {
    bool found = false;
    std::string known;
    for (const NodeSetSettings& s : settings.node_sets) {
      found = found || s.name == name;
      known += (known.empty() ? "" : ", ") + s.name;
    }
    if (!found)
      throw InputError(where + ": node set '" + name + "' is not in model.node_sets (" +
                       (known.empty() ? std::string("there are none") : "there are: " + known) + ")");
  }
}

StepConstraint original(const ModelSettings& settings, const std::string& name) {
  for (const NodeSetSettings& s : settings.node_sets)
    if (s.name == name) return s.constraint == Constraint::Fixed ? StepConstraint::Fixed : StepConstraint::Sliding;
  return StepConstraint::Free;  // a set build_model dropped (no node) keeps nothing to constrain
}

Model with_constraints(const Model& model, const ModelSettings& settings, const Constraints& step) {
  Model m = model;
  std::vector<NodeSet> kept;
  for (NodeSet& set : m.node_sets) {
    const auto it = step.find(set.name);
    const StepConstraint c = it != step.end() ? it->second : original(settings, set.name);
    if (c == StepConstraint::Free) continue;
    if (c == StepConstraint::Fixed) {
      set.constraint = Constraint::Fixed;
      set.normals.clear();
    } else {
      set.constraint = Constraint::Sliding;  // its normals were built (settings_for_steps)
    }
    kept.push_back(std::move(set));
  }
  m.node_sets = std::move(kept);
  return m;
}

}  // namespace

ModelSettings settings_for_steps(const ModelSettings& settings, const Prone2SupineSettings& p2s) {
  check_names(settings, p2s.unloading_constraints, "prone2supine.unloading.constraints");
  check_names(settings, p2s.supine_constraints, "prone2supine.supine.constraints");
  ModelSettings s = settings;
  for (NodeSetSettings& set : s.node_sets) {
    bool slides = false;
    for (const Constraints* step : {&p2s.unloading_constraints, &p2s.supine_constraints}) {
      const auto it = step->find(set.name);
      slides = slides || (it != step->end() && it->second == StepConstraint::Sliding);
    }
    if (!slides) continue;
    if (set.selection.kind == SetSelection::Kind::Box)
      throw InputError("prone2supine: node set '" + set.name +
                       "' is a box selection and cannot slide (no surface normal); select it by an interface "
                       "(between) or a plane");
    set.constraint = Constraint::Sliding;
  }
  return s;
}

Model unloading_model(const Model& model, const ModelSettings& settings, const Prone2SupineSettings& p2s) {
  return with_constraints(model, settings, p2s.unloading_constraints);
}

Model supine_model(const Model& model, const ModelSettings& settings, const Prone2SupineSettings& p2s,
                   const std::vector<Eigen::Vector3d>& reference_nodes) {
  Model m = with_constraints(model, settings, p2s.supine_constraints);
  m.nodes = reference_nodes;
  m.gravity.acceleration_m_s2 = p2s.supine_gravity.acceleration();
  m.gravity.name = p2s.supine_gravity.direction;
  return m;
}

ReferenceStateOptions reference_state_options(const Prone2SupineSettings& p2s, int threads) {
  ReferenceStateOptions o;
  o.tolerance_mm = p2s.tolerance_mm;
  o.max_iterations = p2s.max_iterations;
  o.relaxation_initial = p2s.relaxation_initial;
  o.relaxation_growth = p2s.relaxation_growth;
  o.relaxation_cut = p2s.relaxation_cut;
  o.anderson_memory = p2s.anderson_memory;
  o.threads = threads;
  return o;
}

}  // namespace tissuemesh
