// make_law: the HyperelasticLaw of a MaterialSpec, with stresses in a chosen unit system's stress
// unit (the solver works in the model's units; tests use SI).
#pragma once

#include "core/material_spec.h"
#include "core/unit_system.h"
#include "materials/hyperelastic_law.h"

#include <memory>

namespace tissuemesh {

std::unique_ptr<HyperelasticLaw> make_law(const MaterialSpec& spec,
                                          UnitSystem units = UnitSystem::SI);

}  // namespace tissuemesh
