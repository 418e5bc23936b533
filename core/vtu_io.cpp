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
#include <vtkType.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLDataElement.h>
#include <vtkXMLDataParser.h>
#include <vtkZLibDataCompressor.h>
#include <vtkLZ4DataCompressor.h>
#include <vtkLZMADataCompressor.h>
#include <vtkSmartPointer.h>
#include <vtkXMLUnstructuredGridReader.h>
#include <vtkXMLUnstructuredGridWriter.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <cstring>
#include <limits>
#include <type_traits>
#include <vector>

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

// The most nodes a VTK cell of fixed size has (the tri-quadratic hexahedron's 27): offsets that
// declare more per cell on average are not a mesh.
constexpr std::uint64_t kMaxNodesPerCell = 27;

template <typename T>
std::vector<std::uint64_t> offsets_as_read(const std::vector<unsigned char>& bytes, std::size_t n,
                                           const std::string& path) {
  std::vector<std::uint64_t> out(n);
  for (std::size_t i = 0; i < n; ++i) {
    T v;
    std::memcpy(&v, bytes.data() + i * sizeof(T), sizeof(T));
    if constexpr (std::is_signed_v<T>) {
      if (v < 0) throw InputError(path + ": cell offset " + std::to_string(i) + " is negative");
    }
    out[i] = static_cast<std::uint64_t>(v);
  }
  return out;
}

// Every piece's cell offsets, read with VTK's XML data parser on a stream of its own before the
// reader reads the cells: vtkXMLUnstructuredDataReader allocates the connectivity array from the
// last offset, unchecked, so one corrupt value asks for gigabytes. Refused: offsets that are not
// integers, fewer than the cells, decreasing, or declaring more than kMaxNodesPerCell nodes per
// cell. `text` is the file's text when it was patched (vtk_xml_guard.h), else "".
void require_cell_offsets(const std::string& path, const std::string& text) {
  std::ifstream file;
  std::istringstream patched(text);
  if (text.empty()) file.open(path, std::ios::binary);
  std::istream& stream = text.empty() ? static_cast<std::istream&>(file) : patched;
  vtkNew<vtkXMLDataParser> parser;
  parser->SetStream(&stream);
  if (!stream || parser->Parse() == 0) return;  // VTK's reader reports an unparsable file
  vtkXMLDataElement* root = parser->GetRootElement();
  vtkXMLDataElement* grid = root != nullptr ? root->FindNestedElementWithName("UnstructuredGrid") : nullptr;
  if (grid == nullptr) return;
  if (const char* compressor = root->GetAttribute("compressor")) {
    vtkSmartPointer<vtkDataCompressor> c;
    if (std::strcmp(compressor, "vtkZLibDataCompressor") == 0) c = vtkSmartPointer<vtkZLibDataCompressor>::New();
    else if (std::strcmp(compressor, "vtkLZ4DataCompressor") == 0) c = vtkSmartPointer<vtkLZ4DataCompressor>::New();
    else if (std::strcmp(compressor, "vtkLZMADataCompressor") == 0) c = vtkSmartPointer<vtkLZMADataCompressor>::New();
    else return;  // VTK's reader refuses an unknown compressor
    parser->SetCompressor(c);
  }
  for (int p = 0; p < grid->GetNumberOfNestedElements(); ++p) {
    vtkXMLDataElement* piece = grid->GetNestedElement(p);
    if (std::strcmp(piece->GetName(), "Piece") != 0) continue;
    long long cells = 0;
    piece->GetScalarAttribute("NumberOfCells", cells);
    vtkXMLDataElement* cell_arrays = piece->FindNestedElementWithName("Cells");
    if (cells <= 0 || cell_arrays == nullptr) continue;
    vtkXMLDataElement* offsets =
        cell_arrays->FindNestedElementWithNameAndAttribute("DataArray", "Name", "offsets");
    if (offsets == nullptr) continue;  // VTK refuses a piece without offsets itself
    int type = 0;
    if (!offsets->GetWordTypeAttribute("type", type)) {
      throw InputError(path + ": the cell offsets array has no valid type");
    }
    const int size = vtkAbstractArray::GetDataTypeSize(type);
    const bool integer = type == VTK_TYPE_INT8 || type == VTK_TYPE_UINT8 || type == VTK_TYPE_INT16 ||
                         type == VTK_TYPE_UINT16 || type == VTK_TYPE_INT32 || type == VTK_TYPE_UINT32 ||
                         type == VTK_TYPE_INT64 || type == VTK_TYPE_UINT64;
    if (!integer) throw InputError(path + ": the cell offsets array is not of an integer type");
    const auto n = static_cast<std::size_t>(cells);
    std::vector<unsigned char> bytes(n * static_cast<std::size_t>(size));
    std::size_t read = 0;
    long long appended = 0;
    if (offsets->GetScalarAttribute("offset", appended)) {
      read = parser->ReadAppendedData(appended, bytes.data(), 0, n, type);
    } else {
      const char* format = offsets->GetAttribute("format");
      const int ascii = format != nullptr && std::strcmp(format, "ascii") == 0;
      read = parser->ReadInlineData(offsets, ascii, bytes.data(), 0, n, type);
    }
    if (read < n) {
      throw InputError(path + ": the cell offsets array holds " + std::to_string(read) +
                       " values for " + std::to_string(n) + " cells");
    }
    std::vector<std::uint64_t> values;
    switch (type) {
      case VTK_TYPE_INT8: values = offsets_as_read<std::int8_t>(bytes, n, path); break;
      case VTK_TYPE_UINT8: values = offsets_as_read<std::uint8_t>(bytes, n, path); break;
      case VTK_TYPE_INT16: values = offsets_as_read<std::int16_t>(bytes, n, path); break;
      case VTK_TYPE_UINT16: values = offsets_as_read<std::uint16_t>(bytes, n, path); break;
      case VTK_TYPE_INT32: values = offsets_as_read<std::int32_t>(bytes, n, path); break;
      case VTK_TYPE_UINT32: values = offsets_as_read<std::uint32_t>(bytes, n, path); break;
      case VTK_TYPE_INT64: values = offsets_as_read<std::int64_t>(bytes, n, path); break;
      default: values = offsets_as_read<std::uint64_t>(bytes, n, path); break;
    }
    for (std::size_t i = 1; i < n; ++i) {
      if (values[i] < values[i - 1]) {
        throw InputError(path + ": cell offsets decrease at cell " + std::to_string(i));
      }
    }
    if (values.back() > n * kMaxNodesPerCell) {
      throw InputError(path + ": the cell offsets declare " + std::to_string(values.back()) +
                       " node indices for " + std::to_string(n) + " cells (corrupt offsets)");
    }
  }
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
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) throw InputError(path + ": no such mesh file");
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
  require_cell_offsets(path, patched);
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
