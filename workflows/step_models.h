// The models of the two prone-to-supine steps (docs/prone-to-supine.md): the same mesh, tissues
// and materials, each step with its own node-set constraints and gravity.
//
//   unloading: the imaged (prone) geometry, the model's gravity (prone), unloading constraints
//   supine:    the estimated reference geometry, the supine gravity, supine constraints
//
// A step's constraints map node-set names to fixed | sliding | free; a set the step does not name
// keeps the constraint of model.node_sets. A free set constrains nothing in that step. A sliding
// set uses the unit normals the model was built with (those of the imaged geometry: the chest wall,
// where sets usually lie, is fixed or slides in its plane, so it keeps its shape).
#pragma once

#include "core/model.h"
#include "core/model_settings.h"
#include "workflows/prone2supine_settings.h"
#include "workflows/reference_state.h"

#include <Eigen/Core>

#include <vector>

namespace tissuemesh {

/// The model settings to build the prone model with: every set that a step makes sliding is built
/// as sliding, so that it carries its normals. Throws InputError for a step that names a set the
/// settings do not have (naming the step, the set and the sets there are), or a box selection
/// asked to slide (it has no surface normal).
ModelSettings settings_for_steps(const ModelSettings& settings, const Prone2SupineSettings& p2s);

/// `model` (built from settings_for_steps) with the unloading step's constraints, using the
/// original `settings` for sets the step does not name.
Model unloading_model(const Model& model, const ModelSettings& settings, const Prone2SupineSettings& p2s);

/// `model` with every node at `reference_nodes` (mm, one per model node), the supine gravity and
/// the supine step's constraints.
Model supine_model(const Model& model, const ModelSettings& settings, const Prone2SupineSettings& p2s,
                   const std::vector<Eigen::Vector3d>& reference_nodes);

/// The reference-state iteration's options from the `prone2supine:` section, with `threads`
/// assembly threads.
ReferenceStateOptions reference_state_options(const Prone2SupineSettings& p2s, int threads);

}  // namespace tissuemesh
