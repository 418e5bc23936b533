// The model as a VTU for ParaView: tet4 (VTK_TETRA) or tet10 (VTK_QUADRATIC_TETRA, same node
// order as the Model), coordinates in mm (LPS), cell data `tissue_id` and per-tissue parameters
// in SI (`shear_modulus_Pa`, `bulk_modulus_Pa`, `density_kg_m3`), point data one 0/1 array per
// node set (`set_<name>`), field data tissue_names, material laws and units.
#pragma once

#include "core/model.h"

#include <string>

namespace tissuemesh {

/// Throws OutputError naming the path when it cannot be written.
void write_model_vtu(const Model& model, const std::string& path);

}  // namespace tissuemesh
