#include "core/vtu_io.h"

#include "core/errors.h"
#include "core/memory_budget.h"
#include "core/vtk_xml_guard.h"
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

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>

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

namespace {

// The point and cell counts the file declares, refused when what they need cannot fit: three
// doubles a point, and per cell its four ids, offset, type and tissue id in VTK's arrays and again
// in the TetMesh.
void require_mesh_memory(vtkXMLUnstructuredGridReader& reader, const std::string& path) {
  const vtkIdType points = reader.GetNumberOfPoints(), cells = reader.GetNumberOfCells();
  if (points < 0 || cells < 0) throw InputError(path + ": negative point or cell count");
  const std::uint64_t point_bytes = checked_multiply(static_cast<std::uint64_t>(points), 2 * 24, path);
  const std::uint64_t cell_bytes = checked_multiply(static_cast<std::uint64_t>(cells), 2 * 64, path);
  const std::uint64_t bytes = point_bytes > std::numeric_limits<std::uint64_t>::max() - cell_bytes
                                  ? std::numeric_limits<std::uint64_t>::max()
                                  : point_bytes + cell_bytes;
  require_memory(bytes, path + ": reading this mesh",
                 std::to_string(points) + " points, " + std::to_string(cells) + " cells");
}

// Tissue ids are 1-based indices into the tissue names: a finite whole number in [1, 2^31).
int tissue_id_of(double value, vtkIdType cell, const std::string& path) {
  if (!(value >= 1.0 && value <= static_cast<double>(std::numeric_limits<int>::max())) ||
      value != std::floor(value)) {
    throw InputError(path + ": cell " + std::to_string(cell) + " has tissue_id " +
                     std::to_string(value) + "; tissue ids are whole numbers from 1");
  }
  return static_cast<int>(value);
}

}  // namespace

TetMesh read_vtu(const std::string& path) {
  if (!std::filesystem::is_regular_file(path)) throw InputError(path + ": no such mesh file");
  vtkNew<vtkXMLUnstructuredGridReader> reader;
  if (!reader->CanReadFile(path.c_str()))
    throw InputError(path + ": not a VTK XML unstructured grid (.vtu) file");
  const std::string patched = vtk_xml_text_to_read(path);
  if (patched.empty()) {
    reader->SetFileName(path.c_str());
  } else {
    reader->ReadFromInputStringOn();
    reader->SetInputString(patched);
  }
  reader->UpdateInformation();
  reader->SetupUpdateExtent(0, 1, 0);  // totals the pieces' declared sizes, reads no data
  require_mesh_memory(*reader, path);
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
    const vtkIdType* pts = nullptr;
    vtkIdType npts = 0;
    if (grid->GetCellType(c) == VTK_TETRA) grid->GetCellPoints(c, npts, pts);
    if (npts != 4)
      throw InputError(path + ": cell " + std::to_string(c) +
                       " is not a linear tetrahedron of 4 nodes (only tet meshes are supported)");
    for (int k = 0; k < 4; ++k) {
      if (pts[k] < 0 || pts[k] >= grid->GetNumberOfPoints())
        throw InputError(path + ": cell " + std::to_string(c) + " references node " +
                         std::to_string(pts[k]) + " but there are " +
                         std::to_string(grid->GetNumberOfPoints()) + " nodes");
      mesh.tets[c][k] = static_cast<int>(pts[k]);
    }
  }
  vtkDataArray* ids = grid->GetCellData()->GetArray("tissue_id");
  if (ids == nullptr || ids->GetNumberOfComponents() != 1 || ids->GetNumberOfTuples() != ncells)
    throw InputError(path + ": no 'tissue_id' cell array with one value per cell (one tissue id " +
                     "per tet is required)");
  mesh.tissue_ids.resize(static_cast<std::size_t>(ncells));
  int max_id = 0;
  for (vtkIdType c = 0; c < ncells; ++c) {
    mesh.tissue_ids[c] = tissue_id_of(ids->GetTuple1(c), c, path);
    max_id = std::max(max_id, mesh.tissue_ids[c]);
  }
  mesh.tissue_names = read_string_field(*grid, "tissue_names");
  if (mesh.tissue_names.empty()) {
    // Without names an id needs a default one; ids far above the cell count name no real tissue
    // and would make millions of names.
    if (static_cast<vtkIdType>(max_id) > std::max<vtkIdType>(ncells, 1024))
      throw InputError(path + ": tissue_id " + std::to_string(max_id) + " without tissue names " +
                       "is larger than the number of cells (" + std::to_string(ncells) + ")");
    for (int id = 1; id <= max_id; ++id) mesh.tissue_names.push_back("tissue_" + std::to_string(id));
  }
  mesh.validate(path);
  return mesh;
}

}  // namespace tissuemesh
