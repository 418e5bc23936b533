// The VTU and Gmsh writers, each read back by an independent reader: VTK's XML reader and the
// Gmsh SDK itself (gmsh::open).
#include "core/errors.h"
#include "fe_export/gmsh/write_gmsh.h"
#include "fe_export/vtu/write_model_vtu.h"
#include "support/model_fixture.h"
#include "support/test_paths.h"
#include "support/test_helpers.h"

#include <gmsh.h>
#include <gtest/gtest.h>
#include <vtkCellData.h>
#include <vtkCellType.h>
#include <vtkDataArray.h>
#include <vtkFieldData.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLUnstructuredGridReader.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <set>
#include <stdexcept>

namespace tissuemesh {
namespace {

using test::BlockModelOptions;
using test::block_model;

Model model_of(ElementOrder order) {
  BlockModelOptions o;
  o.order = order;
  o.sliding_top = true;  // a second node set, sharing the edge z = 10, y = 10 with chest_wall
  return block_model(o);
}

std::vector<std::string> strings(vtkUnstructuredGrid* grid, const char* name) {
  std::vector<std::string> out;
  // Text fields are Int32 arrays of one tuple whose component names are the values (meshio reads
  // no String arrays); component i holds i + 1.
  vtkDataArray* a = grid->GetFieldData()->GetArray(name);
  if (a == nullptr || a->GetNumberOfTuples() != 1) return {"<missing>"};
  for (int c = 0; c < a->GetNumberOfComponents(); ++c) {
    out.push_back(a->GetComponentName(c) ? a->GetComponentName(c) : "<unnamed>");
    EXPECT_EQ(a->GetComponent(0, c), c + 1) << name;
  }
  return out;
}

void check_vtu_round_trip(ElementOrder order) {
  const Model m = model_of(order);
  const auto path = (test::scratch_dir() / "model.vtu").string();
  write_model_vtu(m, path);
  vtkNew<vtkXMLUnstructuredGridReader> reader;
  reader->SetFileName(path.c_str());
  reader->Update();
  vtkUnstructuredGrid* grid = reader->GetOutput();
  ASSERT_EQ(grid->GetNumberOfPoints(), static_cast<vtkIdType>(m.nodes.size()));
  for (vtkIdType i = 0; i < grid->GetNumberOfPoints(); ++i) {
    double p[3];
    grid->GetPoint(i, p);
    for (int k = 0; k < 3; ++k) ASSERT_EQ(p[k], m.nodes[i][k]) << i;
  }
  const int npe = m.nodes_per_element();
  const int type = order == ElementOrder::Linear ? VTK_TETRA : VTK_QUADRATIC_TETRA;
  ASSERT_EQ(grid->GetNumberOfCells(), static_cast<vtkIdType>(m.elements.size()));
  vtkCellData* cd = grid->GetCellData();
  vtkDataArray* ids = cd->GetArray("tissue_id");
  vtkDataArray* mu = cd->GetArray("shear_modulus_Pa");
  vtkDataArray* K = cd->GetArray("bulk_modulus_Pa");
  vtkDataArray* rho = cd->GetArray("density_kg_m3");
  ASSERT_TRUE(ids && mu && K && rho);
  EXPECT_EQ(ids->GetDataType(), VTK_INT);
  EXPECT_EQ(mu->GetDataType(), VTK_DOUBLE);
  for (vtkIdType c = 0; c < grid->GetNumberOfCells(); ++c) {
    ASSERT_EQ(grid->GetCellType(c), type);
    const vtkIdType* pts = nullptr;
    vtkIdType n = 0;
    grid->GetCellPoints(c, n, pts);
    ASSERT_EQ(n, npe);
    for (int k = 0; k < npe; ++k) ASSERT_EQ(pts[k], m.elements[c][k]) << c;
    const MaterialSpec& spec = m.materials[m.tissue_ids[c] - 1];
    ASSERT_EQ(ids->GetTuple1(c), m.tissue_ids[c]);
    ASSERT_EQ(mu->GetTuple1(c), spec.mu_Pa);
    ASSERT_EQ(K->GetTuple1(c), spec.K_Pa);
    ASSERT_EQ(rho->GetTuple1(c), spec.density_kg_m3);
  }
  for (const NodeSet& s : m.node_sets) {
    vtkDataArray* a = grid->GetPointData()->GetArray(("set_" + s.name).c_str());
    ASSERT_NE(a, nullptr) << s.name;
    EXPECT_EQ(a->GetDataType(), VTK_UNSIGNED_CHAR);
    const std::set<int> members(s.nodes.begin(), s.nodes.end());
    for (vtkIdType i = 0; i < grid->GetNumberOfPoints(); ++i)
      ASSERT_EQ(a->GetTuple1(i), members.count(static_cast<int>(i)) ? 1.0 : 0.0) << s.name << " node " << i;
  }
  EXPECT_EQ(strings(grid, "tissue_names"), m.tissue_names);
  for (std::size_t t = 0; t < m.tissue_names.size(); ++t) {  // meshio's name -> [tag, dimension]
    vtkDataArray* tag = grid->GetFieldData()->GetArray(m.tissue_names[t].c_str());
    ASSERT_NE(tag, nullptr) << m.tissue_names[t];
    ASSERT_EQ(tag->GetNumberOfTuples(), 2);
    EXPECT_EQ(tag->GetTuple1(0), static_cast<double>(t + 1));
    EXPECT_EQ(tag->GetTuple1(1), 3.0);
  }
  EXPECT_EQ(strings(grid, "material_laws"), (std::vector<std::string>{"neo-hookean", "mooney-rivlin", "mooney-rivlin"}));
  EXPECT_EQ(strings(grid, "coordinate_system"), std::vector<std::string>{"LPS"});
  EXPECT_EQ(strings(grid, "length_unit"), std::vector<std::string>{"mm"});
}

TEST(ModelVtu, Tet4RoundTrip) { check_vtu_round_trip(ElementOrder::Linear); }
TEST(ModelVtu, Tet10RoundTrip) { check_vtu_round_trip(ElementOrder::Quadratic); }

TEST(ModelVtu, UnwritablePathIsAnOutputErrorNamingIt) {
  const auto path = (test::scratch_dir() / "missing_dir" / "model.vtu").string();
  try {
    write_model_vtu(block_model(), path);
    FAIL() << "no error";
  } catch (const OutputError& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
  }
}

TEST(ModelVtu, ExtraArraysRoundTripAndBadOnesAreRefusedBeforeWriting) {
  const Model m = block_model();
  const auto dir = test::scratch_dir();
  ModelVtuData extra;
  VtuArray u{"displacement", 3, {"x", "y", "z"}, {}};
  for (std::size_t i = 0; i < m.nodes.size(); ++i) u.values.insert(u.values.end(), {0.5 * i, -1.0 * i, 2.0});
  extra.point_data.push_back(u);
  std::vector<double> per_cell(m.elements.size());
  for (std::size_t e = 0; e < per_cell.size(); ++e) per_cell[e] = 1.0 + 1e-3 * static_cast<double>(e);
  extra.cell_data.push_back({"J", 1, {}, per_cell});
  extra.field_data.push_back({"load_fraction", 1, {}, {0.75}});
  extra.string_fields.push_back({"stress_unit", {"Pa"}});
  const auto path = (dir / "extra.vtu").string();
  write_model_vtu(m, path, extra);
  vtkNew<vtkXMLUnstructuredGridReader> reader;
  reader->SetFileName(path.c_str());
  reader->Update();
  vtkUnstructuredGrid* grid = reader->GetOutput();
  vtkDataArray* d = grid->GetPointData()->GetArray("displacement");
  ASSERT_NE(d, nullptr);
  ASSERT_EQ(d->GetNumberOfComponents(), 3);
  EXPECT_STREQ(d->GetComponentName(2), "z");
  for (vtkIdType i = 0; i < grid->GetNumberOfPoints(); ++i)
    for (int c = 0; c < 3; ++c) ASSERT_EQ(d->GetComponent(i, c), u.values[3 * i + c]);
  vtkDataArray* J = grid->GetCellData()->GetArray("J");
  ASSERT_NE(J, nullptr);
  for (vtkIdType e = 0; e < grid->GetNumberOfCells(); ++e) ASSERT_EQ(J->GetTuple1(e), per_cell[e]);
  EXPECT_NE(grid->GetCellData()->GetArray("tissue_id"), nullptr) << "the model's own arrays stay";
  EXPECT_EQ(grid->GetFieldData()->GetArray("load_fraction")->GetTuple1(0), 0.75);
  EXPECT_EQ(strings(grid, "stress_unit"), std::vector<std::string>{"Pa"});

  // Programmer errors, refused before the file exists: wrong length, NaN, a name the model has.
  const auto refused = [&](const ModelVtuData& bad, const char* what) {
    const auto p = dir / "bad.vtu";
    EXPECT_THROW(write_model_vtu(m, p.string(), bad), std::invalid_argument) << what;
    EXPECT_FALSE(std::filesystem::exists(p)) << what;
  };
  ModelVtuData bad;
  bad.point_data.push_back({"u", 3, {}, std::vector<double>(3 * m.nodes.size() - 3)});
  refused(bad, "short");
  bad = {};
  bad.cell_data.push_back({"J", 1, {}, per_cell});
  bad.cell_data[0].values[7] = std::nan("");
  refused(bad, "NaN");
  bad = {};
  bad.cell_data.push_back({"tissue_id", 1, {}, per_cell});
  refused(bad, "tissue_id taken");
  bad = {};
  bad.string_fields.push_back({"length_unit", {"m"}});
  refused(bad, "length_unit taken");
}

// gmsh::initialize / finalize for the reading side.
struct GmshReader {
  explicit GmshReader(const std::string& path) {
    gmsh::initialize(0, nullptr, false);
    gmsh::option::setNumber("General.Terminal", 0);
    gmsh::open(path);
  }
  ~GmshReader() { gmsh::finalize(); }
};

// Gmsh tet10 slot of each Model slot: the last two midside nodes are swapped.
constexpr int kGmshSlotOfModelTet10[10] = {0, 1, 2, 3, 4, 5, 6, 7, 9, 8};

void check_gmsh_round_trip(ElementOrder order) {
  const Model m = model_of(order);
  const auto path = (test::scratch_dir() / "model.msh").string();
  write_gmsh(m, path);
  const std::string text = test::read_file(path);
  EXPECT_EQ(text.rfind("$MeshFormat\n4.1 0 8\n", 0), 0u) << "msh 4.1 ASCII";

  GmshReader session(path);
  // Nodes: tags are the 1-based model indices; each node classified once.
  std::vector<std::size_t> node_tags;
  std::vector<double> coords, param;
  gmsh::model::mesh::getNodes(node_tags, coords, param, -1, -1, false, false);
  ASSERT_EQ(node_tags.size(), m.nodes.size());
  std::set<std::size_t> seen;
  for (std::size_t i = 0; i < node_tags.size(); ++i) {
    ASSERT_TRUE(seen.insert(node_tags[i]).second) << "node " << node_tags[i] << " twice";
    ASSERT_GE(node_tags[i], 1u);
    ASSERT_LE(node_tags[i], m.nodes.size());
    // Block coordinates are small integers (midsides odd ones): exact in any decimal format.
    for (int k = 0; k < 3; ++k) ASSERT_EQ(coords[3 * i + k], m.nodes[node_tags[i] - 1][k]) << node_tags[i];
  }

  // Tets: element tag e+1, connectivity back in the Model's order.
  const int npe = m.nodes_per_element();
  std::vector<std::size_t> el_tags, el_nodes;
  gmsh::model::mesh::getElementsByType(order == ElementOrder::Linear ? 4 : 11, el_tags, el_nodes);
  ASSERT_EQ(el_tags.size(), m.elements.size());
  std::set<std::size_t> all_tags;
  for (std::size_t i = 0; i < el_tags.size(); ++i) {
    const std::size_t e = el_tags[i] - 1;
    ASSERT_LT(e, m.elements.size());
    all_tags.insert(el_tags[i]);
    for (int k = 0; k < npe; ++k) {
      const int g = order == ElementOrder::Linear ? k : kGmshSlotOfModelTet10[k];
      ASSERT_EQ(el_nodes[npe * i + g], static_cast<std::size_t>(m.elements[e][k]) + 1) << "element " << e;
    }
  }

  // Independently of the permutation above: every node sits where Gmsh's reference element puts
  // it (getElementProperties local coordinates mapped through the corners). Exact: the block's
  // corners are even integers, so the midpoints are integers.
  {
    std::string type_name;
    int dim = 0, el_order = 0, n_local = 0, n_primary = 0;
    std::vector<double> local;
    gmsh::model::mesh::getElementProperties(order == ElementOrder::Linear ? 4 : 11, type_name, dim, el_order, n_local,
                                            local, n_primary);
    ASSERT_EQ(n_local, npe);
    for (std::size_t i = 0; i < el_tags.size(); ++i) {
      const auto& el = m.elements[el_tags[i] - 1];
      for (int s = 0; s < npe; ++s) {
        const double u = local[3 * s], v = local[3 * s + 1], w = local[3 * s + 2];
        const Eigen::Vector3d x = (1 - u - v - w) * m.nodes[el[0]] + u * m.nodes[el[1]] + v * m.nodes[el[2]] +
                                  w * m.nodes[el[3]];
        ASSERT_EQ(m.nodes[el_nodes[npe * i + s] - 1], x) << "element " << el_tags[i] << " Gmsh slot " << s;
      }
    }
  }

  // Physical groups: one volume group per tissue holding exactly its tets.
  gmsh::vectorpair groups;
  gmsh::model::getPhysicalGroups(groups, 3);
  ASSERT_EQ(groups.size(), m.tissue_names.size());
  for (const auto& [dim, tag] : groups) {
    std::string name;
    gmsh::model::getPhysicalName(dim, tag, name);
    ASSERT_GE(tag, 1);
    ASSERT_LE(tag, static_cast<int>(m.tissue_names.size()));
    EXPECT_EQ(name, m.tissue_names[tag - 1]);
    std::vector<int> entities;
    gmsh::model::getEntitiesForPhysicalGroup(dim, tag, entities);
    std::size_t count = 0;
    for (int ent : entities) {
      std::vector<std::size_t> t, n;
      gmsh::model::mesh::getElementsByType(order == ElementOrder::Linear ? 4 : 11, t, n, ent);
      for (std::size_t et : t) EXPECT_EQ(m.tissue_ids[et - 1], tag) << "element " << et;
      count += t.size();
    }
    EXPECT_EQ(count, static_cast<std::size_t>(std::count(m.tissue_ids.begin(), m.tissue_ids.end(), tag)));
  }

  // Node sets: dim-0 groups whose nodes are the set's.
  gmsh::model::getPhysicalGroups(groups, 0);
  ASSERT_EQ(groups.size(), m.node_sets.size());
  for (const auto& [dim, tag] : groups) {
    std::string name;
    gmsh::model::getPhysicalName(dim, tag, name);
    const NodeSet& s = m.node_sets.at(static_cast<std::size_t>(tag - 1));
    EXPECT_EQ(name, s.name);
    std::vector<std::size_t> tags;
    std::vector<double> xyz;
    gmsh::model::mesh::getNodesForPhysicalGroup(dim, tag, tags, xyz);
    std::set<std::size_t> got(tags.begin(), tags.end()), expected;
    for (int n : s.nodes) expected.insert(static_cast<std::size_t>(n) + 1);
    EXPECT_EQ(got, expected) << s.name;
  }

  // Face sets: a dim-2 group of triangles, outward corners (and tri6 midsides) as in the Model.
  gmsh::model::getPhysicalGroups(groups, 2);
  ASSERT_EQ(groups.size(), m.face_sets.size());
  const FaceSet& skin = m.face_sets.at(0);
  std::string name;
  gmsh::model::getPhysicalName(2, groups[0].second, name);
  EXPECT_EQ(name, skin.name);
  std::vector<int> surfaces;
  gmsh::model::getEntitiesForPhysicalGroup(2, groups[0].second, surfaces);
  ASSERT_EQ(surfaces.size(), 1u);
  std::vector<std::size_t> tri_tags, tri_nodes;
  const int tri_n = order == ElementOrder::Linear ? 3 : 6;
  gmsh::model::mesh::getElementsByType(order == ElementOrder::Linear ? 2 : 9, tri_tags, tri_nodes, surfaces[0]);
  ASSERT_EQ(tri_tags.size(), skin.faces.size());
  for (std::size_t i = 0; i < skin.faces.size(); ++i) {
    const auto& [e, f] = skin.faces[i];
    std::vector<std::size_t> expected;
    for (int c : face_corners(f)) expected.push_back(static_cast<std::size_t>(m.elements[e][c]) + 1);
    if (order == ElementOrder::Quadratic)
      for (int c : face_midsides(f)) expected.push_back(static_cast<std::size_t>(m.elements[e][c]) + 1);
    const std::vector<std::size_t> got(tri_nodes.begin() + tri_n * i, tri_nodes.begin() + tri_n * (i + 1));
    EXPECT_EQ(got, expected) << "face " << i;
    all_tags.insert(tri_tags[i]);
  }
  // Element tags are unique across tets, points and triangles.
  std::vector<int> types;
  std::vector<std::vector<std::size_t>> tags_by_type, nodes_by_type;
  gmsh::model::mesh::getElements(types, tags_by_type, nodes_by_type);
  std::size_t total = 0;
  std::set<std::size_t> unique;
  for (const auto& v : tags_by_type) {
    total += v.size();
    unique.insert(v.begin(), v.end());
  }
  std::size_t set_nodes = 0;
  for (const NodeSet& s : m.node_sets) set_nodes += s.nodes.size();
  EXPECT_EQ(total, m.elements.size() + set_nodes + skin.faces.size());
  EXPECT_EQ(unique.size(), total);
}

TEST(ModelGmsh, Tet4RoundTrip) { check_gmsh_round_trip(ElementOrder::Linear); }
TEST(ModelGmsh, Tet10RoundTripUndoesTheMidsideSwap) { check_gmsh_round_trip(ElementOrder::Quadratic); }

TEST(ModelGmsh, UnwritablePathIsAnOutputErrorNamingIt) {
  const auto path = (test::scratch_dir() / "missing_dir" / "model.msh").string();
  try {
    write_gmsh(block_model(), path);
    FAIL() << "no error";
  } catch (const OutputError& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
  }
  // The SDK was finalized: a second write works.
  const auto ok = (test::scratch_dir() / "model.msh").string();
  EXPECT_NO_THROW(write_gmsh(block_model(), ok));
}

}  // namespace
}  // namespace tissuemesh
