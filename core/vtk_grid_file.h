// Writing VTK XML files with the toolkit's conventions: unstructured grids as VTU, shared by
// core/vtu_io (meshes) and fe_export/vtu (models), and polygonal data as VTP (core/surface_vtp,
// surfaces), so that every file carries the same field data. Needs VTK headers.
#pragma once

#include <vtkPolyData.h>
#include <vtkUnstructuredGrid.h>

#include <string>
#include <vector>

namespace tissuemesh {

/// Adds a string field-data array `name` with `values` to `grid`.
void add_string_field(vtkDataObject& data, const char* name, const std::vector<std::string>& values);

/// Adds the field data every toolkit VTU has (tissue_names, coordinate_system LPS, length_unit mm)
/// and writes `grid` (appended, zlib) to `path`. VTK's own error printing is captured; a failure
/// throws OutputError naming the path.
void write_grid_vtu(vtkUnstructuredGrid& grid, const std::vector<std::string>& tissue_names, const std::string& path);

/// The same for polygonal data, written as VTP.
void write_polydata_vtp(vtkPolyData& data, const std::vector<std::string>& tissue_names, const std::string& path);

}  // namespace tissuemesh
