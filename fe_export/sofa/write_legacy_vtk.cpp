// Legacy VTK 4.2 ASCII unstructured grid for SOFA's MeshVTKLoader (VTK File Formats, "Simple
// Legacy Formats"; docs/formats.md, "SOFA").
#include "fe_export/sofa/write_sofa.h"

#include "fe_export/text_format.h"

namespace tissuemesh {

namespace {

// The header's title line: one line, at most 255 characters (VTK file format).
std::string title_line(const Model& model) {
  std::string t = "tissuemesh model";
  if (!model.title.empty()) t += ": " + model.title;
  t += " (corner nodes, length unit " + length_unit(model.units) + ", LPS)";
  for (char& c : t)
    if (c == '\n' || c == '\r') c = ' ';
  if (t.size() > 255) t.resize(255);
  return t;
}

}  // namespace

void write_legacy_vtk(const Model& model, std::ostream& out) {
  validate_model(model);  // every writer refuses an invalid model first, also when called directly
  const std::size_t n_points = static_cast<std::size_t>(model.num_corner_nodes);
  const std::size_t n_cells = model.elements.size();
  std::string s;
  s.reserve(64 * n_points + 48 * n_cells + 256);
  s += "# vtk DataFile Version 4.2\n";
  s += title_line(model) + "\n";
  s += "ASCII\n";
  s += "DATASET UNSTRUCTURED_GRID\n";
  s += "POINTS " + std::to_string(n_points) + " double\n";
  // One factor (exactly 1 for millimetre systems) keeps mm coordinates bit-identical;
  // length_from_mm(mm-t-s, 18) goes through metres and returns 18.000000000000004.
  const double scale = length_from_mm(model.units, 1.0);
  for (std::size_t i = 0; i < n_points; ++i) {
    const Eigen::Vector3d& x = model.nodes[i];
    s += shortest_decimal(x.x() * scale) + " " + shortest_decimal(x.y() * scale) + " " + shortest_decimal(x.z() * scale) + "\n";
  }
  s += "CELLS " + std::to_string(n_cells) + " " + std::to_string(5 * n_cells) + "\n";
  for (const auto& el : model.elements)
    s += "4 " + std::to_string(el[0]) + " " + std::to_string(el[1]) + " " + std::to_string(el[2]) + " " +
         std::to_string(el[3]) + "\n";
  s += "CELL_TYPES " + std::to_string(n_cells) + "\n";
  for (std::size_t e = 0; e < n_cells; ++e) s += "10\n";
  s += "CELL_DATA " + std::to_string(n_cells) + "\n";
  s += "SCALARS tissue_id int 1\n";
  s += "LOOKUP_TABLE default\n";
  for (int id : model.tissue_ids) s += std::to_string(id) + "\n";
  out << s;
}

}  // namespace tissuemesh
