// Writing a VTK unstructured grid as the toolkit's VTU: shared by core/vtu_io (meshes) and
// fe_export/vtu (models) so that both files carry the same conventions. Needs VTK headers.
#pragma once

#include <vtkUnstructuredGrid.h>

#include <string>
#include <vector>

namespace tissuemesh {

/// Adds a string field-data array `name` with `values` to `grid`.
void add_string_field(vtkUnstructuredGrid& grid, const char* name, const std::vector<std::string>& values);

/// Adds the field data every toolkit VTU has (tissue_names, coordinate_system LPS, length_unit mm)
/// and writes `grid` (appended, zlib) to `path`. VTK's own error printing is captured; a failure
/// throws OutputError naming the path.
void write_grid_vtu(vtkUnstructuredGrid& grid, const std::vector<std::string>& tissue_names, const std::string& path);

}  // namespace tissuemesh
