#include "fe_export/gmsh/gmsh_quality.h"

#include "core/errors.h"
#include "fe_export/gmsh/gmsh_session.h"

#include <algorithm>
#include <cmath>
#include <exception>
#include <fstream>
#include <sstream>

namespace tissuemesh {

namespace {

constexpr int kTet4 = 4;  // Gmsh element type

void build(const TetMesh& mesh) {
  gmsh_sdk::add_model("quality");
  gmsh_sdk::add_discrete_entity(3, 1);
  std::vector<std::size_t> node_tags(mesh.points.size());
  std::vector<double> coords;
  coords.reserve(3 * mesh.points.size());
  for (std::size_t i = 0; i < mesh.points.size(); ++i) {
    node_tags[i] = i + 1;
    coords.insert(coords.end(), mesh.points[i].data(), mesh.points[i].data() + 3);
  }
  gmsh_sdk::add_nodes(3, 1, node_tags, coords);
  std::vector<std::size_t> element_tags(mesh.tets.size()), element_nodes;
  element_nodes.reserve(4 * mesh.tets.size());
  for (std::size_t e = 0; e < mesh.tets.size(); ++e) {
    element_tags[e] = e + 1;
    for (int n : mesh.tets[e]) element_nodes.push_back(static_cast<std::size_t>(n) + 1);
  }
  gmsh_sdk::add_elements_by_type(1, kTet4, element_tags, element_nodes);
  gmsh_sdk::add_physical_group(3, {1}, 1);
}

// Column index of `name` in the view header T2(...){"SICN","Gamma"};
int column_of(const std::string& header, const std::string& name) {
  const std::size_t open = header.find('{');
  std::istringstream names(header.substr(open + 1));
  std::string field;
  for (int k = 0; std::getline(names, field, ','); ++k)
    if (field.find('"' + name + '"') != std::string::npos) return k;
  return -1;
}

// Reads the SS(x0,y0,z0,...,z3){v...} records (4 nodal values per field) and checks each against
// the tet it must describe: Gmsh writes the elements of one entity in the order they were added.
std::vector<GmshTetQuality> read_statistics(const TetMesh& mesh, const std::string& path) {
  std::ifstream in(path);
  std::string line, header;
  while (std::getline(in, line) && line.rfind("T2(", 0) != 0) {
  }
  header = line;
  const int sicn_col = column_of(header, "SICN"), gamma_col = column_of(header, "Gamma");
  if (header.empty() || sicn_col < 0 || gamma_col < 0)
    throw OutputError(path + ": Gmsh's statistics view has no SICN and Gamma columns");

  // %g keeps 6 significant digits of each coordinate: compare to that, scaled by the mesh size.
  double extent = 0;
  for (const auto& p : mesh.points) extent = std::max(extent, p.cwiseAbs().maxCoeff());
  const double coordinate_tolerance = 1e-5 * std::max(extent, 1.0);

  std::vector<GmshTetQuality> out;
  out.reserve(mesh.tets.size());
  while (std::getline(in, line) && line.rfind("SS(", 0) == 0) {
    const std::size_t e = out.size();
    if (e >= mesh.tets.size()) break;
    std::replace(line.begin(), line.end(), ',', ' ');
    std::replace(line.begin(), line.end(), '(', ' ');
    std::replace(line.begin(), line.end(), ')', ' ');
    std::replace(line.begin(), line.end(), '{', ' ');
    std::replace(line.begin(), line.end(), '}', ' ');
    std::replace(line.begin(), line.end(), ';', ' ');
    std::istringstream fields(line.substr(2));
    std::vector<double> v;
    for (double x; fields >> x;) v.push_back(x);
    const std::size_t needed = 12 + 4 * static_cast<std::size_t>(std::max(sicn_col, gamma_col) + 1);
    if (v.size() < needed || (v.size() - 12) % 4 != 0)
      throw OutputError(path + ": malformed record " + std::to_string(e + 1));
    for (int k = 0; k < 4; ++k)
      for (int c = 0; c < 3; ++c)
        if (std::abs(v[3 * k + c] - mesh.points[static_cast<std::size_t>(mesh.tets[e][k])][c]) > coordinate_tolerance)
          throw OutputError(path + ": record " + std::to_string(e + 1) + " is not at tet " + std::to_string(e) +
                            "'s nodes");
    out.push_back({v[12 + 4 * static_cast<std::size_t>(gamma_col)], v[12 + 4 * static_cast<std::size_t>(sicn_col)]});
  }
  if (out.size() != mesh.tets.size())
    throw OutputError(path + ": Gmsh wrote " + std::to_string(out.size()) + " quality records for " +
                      std::to_string(mesh.tets.size()) + " tets");
  return out;
}

}  // namespace

GmshQuality gmsh_tet_quality(const TetMesh& mesh, const std::string& pos_path) {
  mesh.validate("Gmsh quality");
  GmshQuality result;
  try {
    GmshSession session;
    build(mesh);
    gmsh_sdk::set_number("Print.PostElementary", 0);
    gmsh_sdk::set_number("Print.PostElement", 0);
    gmsh_sdk::set_number("Print.PostSICN", 1);
    gmsh_sdk::set_number("Print.PostGamma", 1);
    gmsh_sdk::set_number("Mesh.SaveAll", 1);
    gmsh_sdk::write(pos_path);
    result.version = gmsh_sdk::get_string("General.Version");
  } catch (const std::exception& e) {  // Gmsh's message, or why the SDK could not be loaded
    throw OutputError(pos_path + ": Gmsh cannot write its quality statistics: " + e.what());
  }
  result.tets = read_statistics(mesh, pos_path);
  return result;
}

}  // namespace tissuemesh
