#include "core/vtu_io.h"

#include "core/errors.h"
#include "core/vtk_grid_file.h"

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkCellType.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkIdTypeArray.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkPoints.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLUnstructuredGridReader.h>
#include <vtkXMLUnstructuredGridWriter.h>

#include <filesystem>

namespace tissuemesh {

void write_vtu(const TetMesh& mesh, const std::string& path, const CellScalars& extra) {
  mesh.validate(path);
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(static_cast<vtkIdType>(mesh.points.size()));
  for (std::size_t i = 0; i < mesh.points.size(); ++i)
    points->SetPoint(static_cast<vtkIdType>(i), mesh.points[i].data());

  vtkNew<vtkIdTypeArray> offsets, connectivity;
  offsets->SetNumberOfValues(static_cast<vtkIdType>(mesh.tets.size() + 1));
  connectivity->SetNumberOfValues(static_cast<vtkIdType>(4 * mesh.tets.size()));
  for (std::size_t t = 0; t <= mesh.tets.size(); ++t) offsets->SetValue(t, 4 * t);
  for (std::size_t t = 0; t < mesh.tets.size(); ++t)
    for (int k = 0; k < 4; ++k) connectivity->SetValue(4 * t + k, mesh.tets[t][k]);
  vtkNew<vtkCellArray> cells;
  cells->SetData(offsets, connectivity);

  vtkNew<vtkUnstructuredGrid> grid;
  grid->SetPoints(points);
  grid->SetCells(VTK_TETRA, cells);

  vtkNew<vtkIntArray> ids;
  ids->SetName("tissue_id");
  ids->SetNumberOfValues(static_cast<vtkIdType>(mesh.tets.size()));
  for (std::size_t t = 0; t < mesh.tets.size(); ++t) ids->SetValue(t, mesh.tissue_ids[t]);
  grid->GetCellData()->AddArray(ids);
  grid->GetCellData()->SetActiveScalars("tissue_id");
  for (const auto& [name, values] : extra) {
    if (values.size() != mesh.tets.size())
      throw OutputError(path + ": cell array '" + name + "' has the wrong length");
    vtkNew<vtkDoubleArray> a;
    a->SetName(name.c_str());
    a->SetNumberOfValues(static_cast<vtkIdType>(values.size()));
    for (std::size_t t = 0; t < values.size(); ++t) a->SetValue(t, values[t]);
    grid->GetCellData()->AddArray(a);
  }
  write_grid_vtu(*grid, mesh.tissue_names, path);
}

TetMesh read_vtu(const std::string& path) {
  if (!std::filesystem::is_regular_file(path)) throw InputError(path + ": no such mesh file");
  vtkNew<vtkXMLUnstructuredGridReader> reader;
  if (!reader->CanReadFile(path.c_str()))
    throw InputError(path + ": not a VTK XML unstructured grid (.vtu) file");
  reader->SetFileName(path.c_str());
  reader->Update();
  vtkUnstructuredGrid* grid = reader->GetOutput();
  if (reader->GetErrorCode() != 0 || grid == nullptr || grid->GetNumberOfPoints() == 0)
    throw InputError(path + ": cannot read mesh (corrupt or truncated .vtu)");

  TetMesh mesh;
  mesh.points.resize(static_cast<std::size_t>(grid->GetNumberOfPoints()));
  for (vtkIdType i = 0; i < grid->GetNumberOfPoints(); ++i) grid->GetPoint(i, mesh.points[i].data());

  const vtkIdType ncells = grid->GetNumberOfCells();
  mesh.tets.resize(static_cast<std::size_t>(ncells));
  for (vtkIdType c = 0; c < ncells; ++c) {
    if (grid->GetCellType(c) != VTK_TETRA)
      throw InputError(path + ": cell " + std::to_string(c) +
                       " is not a linear tetrahedron (only tet meshes are supported)");
    const vtkIdType* pts = nullptr;
    vtkIdType npts = 0;
    grid->GetCellPoints(c, npts, pts);
    for (int k = 0; k < 4; ++k) mesh.tets[c][k] = static_cast<int>(pts[k]);
  }
  vtkDataArray* ids = grid->GetCellData()->GetArray("tissue_id");
  if (ids == nullptr || ids->GetNumberOfComponents() != 1)
    throw InputError(path + ": no 'tissue_id' cell array (one tissue id per tet is required)");
  mesh.tissue_ids.resize(static_cast<std::size_t>(ncells));
  int max_id = 0;
  for (vtkIdType c = 0; c < ncells; ++c) {
    mesh.tissue_ids[c] = static_cast<int>(ids->GetTuple1(c));
    max_id = std::max(max_id, mesh.tissue_ids[c]);
  }
  mesh.tissue_names = read_string_field(*grid, "tissue_names");
  if (mesh.tissue_names.empty()) {
    for (int id = 1; id <= max_id; ++id) mesh.tissue_names.push_back("tissue_" + std::to_string(id));
  }
  mesh.validate(path);
  return mesh;
}

}  // namespace tissuemesh
