// The model as a VTU (VTK XML unstructured grid) for ParaView; conventions of core/vtu_io.
#include "fe_export/vtu/write_model_vtu.h"

#include "core/errors.h"
#include "core/vtk_grid_file.h"

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkCellType.h>
#include <vtkCommand.h>
#include <vtkDoubleArray.h>
#include <vtkExecutive.h>
#include <vtkFieldData.h>
#include <vtkIdTypeArray.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkUnsignedCharArray.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLUnstructuredGridWriter.h>

#include <cmath>
#include <functional>
#include <stdexcept>
#include <string>

namespace tissuemesh {

namespace {

// One Float64 cell array holding a per-tissue value (SI) for every element.
vtkNew<vtkDoubleArray> tissue_cell_array(const Model& model, const char* name,
                                         const std::function<double(const MaterialSpec&)>& value) {
  vtkNew<vtkDoubleArray> a;
  a->SetName(name);
  a->SetNumberOfValues(static_cast<vtkIdType>(model.elements.size()));
  for (std::size_t e = 0; e < model.elements.size(); ++e)
    a->SetValue(static_cast<vtkIdType>(e), value(model.materials[static_cast<std::size_t>(model.tissue_ids[e] - 1)]));
  return a;
}

// Refuses an empty name or one `data` already has (for field data also the names write_grid_vtu
// adds), so that an extra array never silently replaces one of the model's.
void check_new_name(const std::string& name, vtkFieldData& data, bool field, const std::string& what) {
  if (name.empty()) throw std::invalid_argument(what + ": empty name");
  if (data.GetAbstractArray(name.c_str()) != nullptr ||
      (field && (name == "tissue_names" || name == "coordinate_system" || name == "length_unit")))
    throw std::invalid_argument(what + ": the file already has an array of that name");
}

// `a` as a VTK array of `tuples` tuples (any count when tuples < 0) for `data`, refusing a wrong
// length, a non-finite value or a name already taken.
vtkNew<vtkDoubleArray> extra_array(const VtuArray& a, vtkIdType tuples, vtkFieldData& data, const char* kind) {
  const std::string what = std::string("write_model_vtu: ") + kind + " array '" + a.name + "'";
  check_new_name(a.name, data, std::string(kind) == "field", what);
  if (a.components < 1 || a.values.size() % static_cast<std::size_t>(a.components) != 0 ||
      (!a.component_names.empty() && a.component_names.size() != static_cast<std::size_t>(a.components)))
    throw std::invalid_argument(what + ": inconsistent components");
  const auto n = static_cast<vtkIdType>(a.values.size() / static_cast<std::size_t>(a.components));
  if (tuples >= 0 && n != tuples)
    throw std::invalid_argument(what + ": " + std::to_string(n) + " tuples, expected " + std::to_string(tuples));
  vtkNew<vtkDoubleArray> out;
  out->SetName(a.name.c_str());
  out->SetNumberOfComponents(a.components);
  for (std::size_t c = 0; c < a.component_names.size(); ++c)
    out->SetComponentName(static_cast<vtkIdType>(c), a.component_names[c].c_str());
  out->SetNumberOfTuples(n);
  for (std::size_t i = 0; i < a.values.size(); ++i) {
    if (!std::isfinite(a.values[i])) throw std::invalid_argument(what + ": non-finite value at " + std::to_string(i));
    out->SetValue(static_cast<vtkIdType>(i), a.values[i]);
  }
  return out;
}

}  // namespace

void write_model_vtu(const Model& model, const std::string& path, const ModelVtuData& extra) {
  validate_model(model);  // every writer refuses an invalid model first, also when called directly
  const std::size_t n_nodes = model.nodes.size();
  const std::size_t n_el = model.elements.size();
  const int npe = model.nodes_per_element();

  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(static_cast<vtkIdType>(n_nodes));
  for (std::size_t i = 0; i < n_nodes; ++i) points->SetPoint(static_cast<vtkIdType>(i), model.nodes[i].data());

  // VTK_QUADRATIC_TETRA's midside order (0,1) (1,2) (2,0) (0,3) (1,3) (2,3) is the Model's.
  vtkNew<vtkIdTypeArray> offsets, connectivity;
  offsets->SetNumberOfValues(static_cast<vtkIdType>(n_el + 1));
  connectivity->SetNumberOfValues(static_cast<vtkIdType>(npe * n_el));
  for (std::size_t e = 0; e <= n_el; ++e) offsets->SetValue(static_cast<vtkIdType>(e), static_cast<vtkIdType>(npe * e));
  for (std::size_t e = 0; e < n_el; ++e)
    for (int k = 0; k < npe; ++k) connectivity->SetValue(static_cast<vtkIdType>(npe * e + k), model.elements[e][k]);
  vtkNew<vtkCellArray> cells;
  cells->SetData(offsets, connectivity);

  vtkNew<vtkUnstructuredGrid> grid;
  grid->SetPoints(points);
  grid->SetCells(model.order == ElementOrder::Linear ? VTK_TETRA : VTK_QUADRATIC_TETRA, cells);

  vtkNew<vtkIntArray> ids;
  ids->SetName("tissue_id");
  ids->SetNumberOfValues(static_cast<vtkIdType>(n_el));
  for (std::size_t e = 0; e < n_el; ++e) ids->SetValue(static_cast<vtkIdType>(e), model.tissue_ids[e]);
  grid->GetCellData()->AddArray(ids);
  grid->GetCellData()->SetActiveScalars("tissue_id");
  grid->GetCellData()->AddArray(tissue_cell_array(model, "shear_modulus_Pa", [](const MaterialSpec& m) { return m.mu_Pa; }));
  grid->GetCellData()->AddArray(tissue_cell_array(model, "bulk_modulus_Pa", [](const MaterialSpec& m) { return m.K_Pa; }));
  grid->GetCellData()->AddArray(
      tissue_cell_array(model, "density_kg_m3", [](const MaterialSpec& m) { return m.density_kg_m3; }));

  for (const NodeSet& set : model.node_sets) {
    vtkNew<vtkUnsignedCharArray> member;
    member->SetName(("set_" + set.name).c_str());
    member->SetNumberOfValues(static_cast<vtkIdType>(n_nodes));
    member->FillValue(0);
    for (int n : set.nodes) member->SetValue(n, 1);
    grid->GetPointData()->AddArray(member);
  }

  std::vector<std::string> laws;
  for (const MaterialSpec& m : model.materials) laws.push_back(material_law_name(m.law));
  add_string_field(*grid, "material_laws", laws);

  for (const VtuArray& a : extra.point_data)
    grid->GetPointData()->AddArray(extra_array(a, static_cast<vtkIdType>(n_nodes), *grid->GetPointData(), "point"));
  for (const VtuArray& a : extra.cell_data)
    grid->GetCellData()->AddArray(extra_array(a, static_cast<vtkIdType>(n_el), *grid->GetCellData(), "cell"));
  for (const VtuArray& a : extra.field_data)
    grid->GetFieldData()->AddArray(extra_array(a, -1, *grid->GetFieldData(), "field"));
  for (const auto& [name, values] : extra.string_fields) {
    check_new_name(name, *grid->GetFieldData(), true, "write_model_vtu: string field '" + name + "'");
    add_string_field(*grid, name.c_str(), values);
  }
  write_grid_vtu(*grid, model.tissue_names, path);
}

}  // namespace tissuemesh
