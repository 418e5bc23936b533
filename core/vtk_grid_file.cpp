#include "core/vtk_grid_file.h"

#include "core/errors.h"

#include <algorithm>

#include <vtkCommand.h>
#include <vtkExecutive.h>
#include <vtkFieldData.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkStringArray.h>
#include <vtkXMLPolyDataWriter.h>
#include <vtkXMLUnstructuredGridWriter.h>

namespace tissuemesh {

namespace {
// Observing ErrorEvent keeps VTK from printing its error (the library never prints); the
// failure is reported through OutputError instead.
class ErrorCapture : public vtkCommand {
 public:
  static ErrorCapture* New() { return new ErrorCapture; }
  void Execute(vtkObject*, unsigned long, void*) override { failed = true; }
  bool failed = false;
};

template <typename Writer, typename Data>
void write_xml(Data& data, const std::vector<std::string>& tissue_names, const std::string& path, const char* kind) {
  add_string_field(data, "tissue_names", tissue_names);
  add_string_field(data, "coordinate_system", {"LPS"});
  add_string_field(data, "length_unit", {"mm"});
  add_tissue_tags(data, tissue_names);
  vtkNew<Writer> writer;
  writer->SetFileName(path.c_str());
  writer->SetInputData(&data);
  writer->SetDataModeToAppended();
  writer->SetCompressorTypeToZLib();
  // zlib's fastest level: about a third faster to write than VTK's default level 5 for a file
  // about 1 % larger; any zlib reader reads every level.
  writer->SetCompressionLevel(1);
  vtkNew<ErrorCapture> errors;
  writer->AddObserver(vtkCommand::ErrorEvent, errors);
  writer->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, errors);  // "returned failure" report
  if (writer->Write() != 1 || errors->failed)
    throw OutputError(path + ": cannot write " + kind + " file (missing or read-only directory, or disk full?)");
}
}  // namespace

// Text as VTK component names: meshio (5.x) refuses String arrays anywhere in a VTU, while VTK's
// XML writer and reader keep component names (ComponentName0, ...) on any array, and ParaView's
// spreadsheet shows them as column headers. Value i + 1 sits under the name of value i, so the
// tissue_names array also maps each tissue id to its name.
void add_string_field(vtkDataObject& data, const char* name, const std::vector<std::string>& values) {
  vtkNew<vtkIntArray> a;
  a->SetName(name);
  a->SetNumberOfComponents(static_cast<int>(std::max<std::size_t>(values.size(), 1)));
  a->SetNumberOfTuples(values.empty() ? 0 : 1);
  for (std::size_t i = 0; i < values.size(); ++i) {
    a->SetComponentName(static_cast<vtkIdType>(i), values[i].c_str());
    a->SetTypedComponent(0, static_cast<int>(i), static_cast<int>(i + 1));
  }
  data.GetFieldData()->AddArray(a);
}

std::vector<std::string> read_string_field(vtkDataObject& data, const char* name) {
  vtkAbstractArray* a = data.GetFieldData()->GetAbstractArray(name);
  std::vector<std::string> values;
  if (a == nullptr) return values;
  if (auto* text = vtkStringArray::SafeDownCast(a)) {  // VTK string arrays, as some files hold them
    for (vtkIdType i = 0; i < text->GetNumberOfValues(); ++i) values.push_back(text->GetValue(i));
    return values;
  }
  if (a->GetNumberOfTuples() != 1) return values;
  for (int c = 0; c < a->GetNumberOfComponents(); ++c) {
    const char* component = a->GetComponentName(c);
    values.push_back(component != nullptr ? component : "");
  }
  return values;
}

// meshio's convention for named regions (its Gmsh reader and writer): field_data[name] = [tag,
// dimension]. A tissue name that is already an array of the file would replace it, so it is refused.
void add_tissue_tags(vtkDataObject& data, const std::vector<std::string>& tissue_names) {
  for (std::size_t t = 0; t < tissue_names.size(); ++t) {
    const std::string& name = tissue_names[t];
    if (data.GetFieldData()->GetAbstractArray(name.c_str()) != nullptr)
      throw InputError("tissue name '" + name + "' is also the name of a field-data array of the output file; rename the tissue");
    vtkNew<vtkIntArray> a;
    a->SetName(name.c_str());
    a->SetNumberOfValues(2);
    a->SetValue(0, static_cast<int>(t + 1));
    a->SetValue(1, 3);
    data.GetFieldData()->AddArray(a);
  }
}

void write_grid_vtu(vtkUnstructuredGrid& grid, const std::vector<std::string>& tissue_names, const std::string& path) {
  write_xml<vtkXMLUnstructuredGridWriter>(grid, tissue_names, path, "VTU");
}

void write_polydata_vtp(vtkPolyData& data, const std::vector<std::string>& tissue_names, const std::string& path) {
  write_xml<vtkXMLPolyDataWriter>(data, tissue_names, path, "VTP");
}

}  // namespace tissuemesh
