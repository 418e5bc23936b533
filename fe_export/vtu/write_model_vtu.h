// The model as a VTU for ParaView: tet4 (VTK_TETRA) or tet10 (VTK_QUADRATIC_TETRA, same node
// order as the Model), coordinates in mm (LPS), cell data `tissue_id` and per-tissue parameters
// in SI (`shear_modulus_Pa`, `bulk_modulus_Pa`, `density_kg_m3`), point data one 0/1 array per
// node set (`set_<name>`), field data tissue_names, material laws and units. Callers may add
// Float64 point, cell and field arrays and string fields (ModelVtuData), e.g. solve results.
#pragma once

#include "core/model.h"

#include <string>
#include <utility>
#include <vector>

namespace tissuemesh {

/// A Float64 data array added to the model's own (e.g. results): `components` values per tuple,
/// tuple-major (values[components * i + c]).
struct VtuArray {
  std::string name;
  int components = 1;
  std::vector<std::string> component_names;  ///< empty, or one per component (shown by ParaView)
  std::vector<double> values;
};

/// What a result file adds to the model VTU (`tissuemesh solve`'s solution.vtu).
struct ModelVtuData {
  std::vector<VtuArray> point_data;  ///< one tuple per model node, in the model's node order
  std::vector<VtuArray> cell_data;   ///< one tuple per element, in the model's element order
  std::vector<VtuArray> field_data;  ///< any number of tuples (e.g. load_fraction)
  std::vector<std::pair<std::string, std::vector<std::string>>> string_fields;  ///< e.g. units
};

/// Writes the model, plus `extra` arrays. Throws OutputError naming the path when it cannot be
/// written; std::invalid_argument (a programmer error, before anything is written) when an extra
/// array has the wrong length, a non-finite value, or a name the file already has.
void write_model_vtu(const Model& model, const std::string& path, const ModelVtuData& extra = {});

}  // namespace tissuemesh
