// Writing VTK XML files with the toolkit's conventions: unstructured grids as VTU, shared by
// core/vtu_io (meshes) and fe_export/vtu (models), and polygonal data as VTP (core/surface_vtp,
// surfaces), so that every file carries the same field data. Needs VTK headers.
#pragma once

#include <vtkPolyData.h>
#include <vtkUnstructuredGrid.h>

#include <string>
#include <vector>

namespace tissuemesh {

/// Adds a text field-data array `name` holding `values` in a form meshio can read: an Int32 array
/// of one tuple with one component per value, component i named values[i] and holding i + 1.
void add_string_field(vtkDataObject& data, const char* name, const std::vector<std::string>& values);

/// The values of a text field written by add_string_field (or, in older files, a VTK string
/// array); empty when `data` has no such array.
std::vector<std::string> read_string_field(vtkDataObject& data, const char* name);

/// Adds one Int32 field-data array per tissue, named after it and holding [tissue id, 3]
/// (meshio's name -> [tag, dimension] convention). Throws InputError when a tissue name is
/// already the name of an array of `data`.
void add_tissue_tags(vtkDataObject& data, const std::vector<std::string>& tissue_names);

/// Adds the field data every toolkit VTU has (text fields tissue_names, coordinate_system LPS,
/// length_unit mm, then the per-tissue tags) and writes `grid` (appended, zlib) to `path`. VTK's
/// own error printing is captured; a failure throws OutputError naming the path, InputError
/// when a tissue name collides with a field-data array.
void write_grid_vtu(vtkUnstructuredGrid& grid, const std::vector<std::string>& tissue_names, const std::string& path);

/// The same for polygonal data, written as VTP.
void write_polydata_vtp(vtkPolyData& data, const std::vector<std::string>& tissue_names, const std::string& path);

}  // namespace tissuemesh
