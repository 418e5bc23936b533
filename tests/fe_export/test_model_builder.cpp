// build_model on the block fixture: selections, tet10 midside nodes, sliding normals, gravity, and
// the checks every writer relies on (validate_model). Counts are derived by hand from the grid.
#include "core/errors.h"
#include "core/model_builder.h"
#include "core/node_ordering.h"
#include "core/quantity.h"
#include "support/model_fixture.h"
#include "support/test_helpers.h"
#include "support/tolerances.h"

#include <gtest/gtest.h>

#include <numeric>

#include <Eigen/Geometry>

#include <algorithm>
#include <iostream>
#include <map>
#include <set>

using namespace tissuemesh;

namespace {

Eigen::Vector3d face_normal(const Model& m, const std::array<int, 2>& f) {
  const auto& c = face_corners(f[1]);
  const auto& el = m.elements[f[0]];
  return (m.nodes[el[c[1]]] - m.nodes[el[c[0]]]).cross(m.nodes[el[c[2]]] - m.nodes[el[c[0]]]) * 0.5;
}

ModelSettings settings_from(const std::string& yaml) {
  YamlMap map(YAML::Load(yaml), "model", "t.yaml");
  return ModelSettings::from_yaml(map);
}

Model block_in(NodeOrder order, const test::BlockModelOptions& o = {}) {
  ModelSettings s = test::block_settings(o);
  s.node_order = order;
  return build_model(test::block_mesh(), s, test::block_materials(o.ogden_tumor), "t");
}

long long profile(const Model& m) {
  return matrix_profile(static_cast<int>(m.nodes.size()), m.elements, m.nodes_per_element());
}

// Node set as point -> normal (zero for a fixed set): what the set means, whatever the numbering.
std::map<std::array<double, 3>, std::array<double, 3>> by_point(const Model& m, const NodeSet& s) {
  std::map<std::array<double, 3>, std::array<double, 3>> out;
  for (std::size_t i = 0; i < s.nodes.size(); ++i) {
    const Eigen::Vector3d& p = m.nodes[s.nodes[i]];
    const Eigen::Vector3d n = s.normals.empty() ? Eigen::Vector3d::Zero() : s.normals[i];
    out[{p.x(), p.y(), p.z()}] = {n.x(), n.y(), n.z()};
  }
  return out;
}

}  // namespace

TEST(ModelBuilder, LinearBlockHasTheGridsCountsAndSets) {
  const Model m = test::block_model();
  EXPECT_EQ(m.nodes.size(), 11u * 6u * 6u);
  EXPECT_EQ(m.elements.size(), 1500u);
  EXPECT_EQ(m.num_corner_nodes, 396);
  ASSERT_EQ(m.node_sets.size(), 1u);
  EXPECT_EQ(m.node_sets[0].nodes.size(), 11u * 6u);  // the y = 10 face of the grid
  for (int v : m.node_sets[0].nodes) EXPECT_EQ(m.nodes[v].y(), 10.0);
  ASSERT_EQ(m.face_sets.size(), 1u);
  EXPECT_EQ(m.face_sets[0].faces.size(), 10u * 5u * 2u);  // y = 0 face: 50 squares, 2 triangles each
  double area = 0.0;
  for (const auto& f : m.face_sets[0].faces) {
    const Eigen::Vector3d n = face_normal(m, f);
    EXPECT_LT(n.y(), 0.0) << "face normals point out of the body (-y here)";
    area += n.norm();
  }
  EXPECT_NEAR(area, 20.0 * 10.0, 200.0 * test::kRelativeRoundoff);
  EXPECT_EQ(m.gravity.acceleration_m_s2, Eigen::Vector3d(0, -9.81, 0));
}

TEST(ModelBuilder, OutwardFacesCloseEveryElement) {
  // The four outward faces of a tet sum to the zero vector and each points away from the
  // opposite corner: checks face_corners for all four local faces.
  const Model m = test::block_model();
  for (std::size_t e = 0; e < 20; ++e) {
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    for (int f = 0; f < 4; ++f) {
      const Eigen::Vector3d n = face_normal(m, {static_cast<int>(e), f});
      sum += n;
      std::set<int> on_face(face_corners(f).begin(), face_corners(f).end());
      int opposite = 0;
      while (on_face.count(opposite)) ++opposite;
      EXPECT_LT(n.dot(m.nodes[m.elements[e][opposite]] - m.nodes[m.elements[e][face_corners(f)[0]]]), 0.0);
    }
    EXPECT_LT(sum.norm(), 1e-12);
  }
}

TEST(ModelBuilder, QuadraticMidsidesAreSharedEdgeMidpoints) {
  const Model lin = test::block_model();
  test::BlockModelOptions o;
  o.order = ElementOrder::Quadratic;
  const Model m = test::block_model(o);
  std::set<std::pair<int, int>> edges;
  const int kEdge[6][2] = {{0, 1}, {1, 2}, {2, 0}, {0, 3}, {1, 3}, {2, 3}};
  for (const auto& el : lin.elements)
    for (const auto& e : kEdge) edges.insert(std::minmax(el[e[0]], el[e[1]]));
  EXPECT_EQ(m.nodes.size(), lin.nodes.size() + edges.size()) << "one node per edge, shared";
  for (const auto& el : m.elements)
    for (int k = 0; k < 6; ++k)
      EXPECT_EQ(m.nodes[el[4 + k]], 0.5 * (m.nodes[el[kEdge[k][0]]] + m.nodes[el[kEdge[k][1]]]));
  // The fixed y = 10 face: 66 corners + 165 edges (60 along x, 55 along z, 50 diagonals).
  EXPECT_EQ(m.node_sets[0].nodes.size(), 66u + 165u);
  for (int v : m.node_sets[0].nodes) EXPECT_EQ(m.nodes[v].y(), 10.0);
  EXPECT_TRUE(std::is_sorted(m.node_sets[0].nodes.begin(), m.node_sets[0].nodes.end()));
}

TEST(ModelBuilder, InterfaceFacesPointFromSideAToSideB) {
  const Model m = test::block_model();
  InterfaceSide fat, fgt;
  fat.tissues = {"fat"};
  fgt.tissues = {"fgt"};
  double area = 0.0;
  for (const auto& f : interface_faces(m, fat, fgt)) {
    EXPECT_EQ(m.tissue_ids[f[0]], 1);
    const Eigen::Vector3d n = face_normal(m, f);
    EXPECT_GT(n.x(), 0.0);
    area += n.norm();
    for (int c : face_corners(f[1])) EXPECT_EQ(m.nodes[m.elements[f[0]][c]].x(), 8.0);
  }
  EXPECT_NEAR(area, 100.0, 100.0 * test::kRelativeRoundoff);  // the x = 8 plane, 10 x 10 mm
}

TEST(ModelBuilder, SlidingSetCarriesNormalsAndLeavesFixedNodesFixed) {
  test::BlockModelOptions o;
  o.sliding_top = true;
  const Model m = test::block_model(o);
  ASSERT_EQ(m.node_sets.size(), 2u);
  const NodeSet& top = m.node_sets[1];
  EXPECT_EQ(top.constraint, Constraint::Sliding);
  EXPECT_EQ(top.nodes.size(), 11u * 6u - 11u) << "the z = 10 face minus its edge on the fixed y = 10 face";
  for (std::size_t i = 0; i < top.nodes.size(); ++i) {
    EXPECT_EQ(m.nodes[top.nodes[i]].z(), 10.0);
    EXPECT_NE(m.nodes[top.nodes[i]].y(), 10.0);
    EXPECT_EQ(top.normals[i], Eigen::Vector3d(0, 0, 1));
  }
}

TEST(ModelBuilder, InterfaceSlidingNormalsAreAreaWeighted) {
  ModelSettings s = test::block_settings({});
  s.node_sets[0].selection.kind = SetSelection::Kind::Between;
  s.node_sets[0].selection.side_a.tissues = {"tumor"};
  s.node_sets[0].selection.side_b.tissues.clear();
  s.node_sets[0].selection.side_b.outside = true;
  s.node_sets[0].constraint = Constraint::Sliding;
  const Model m = build_model(test::block_mesh(), s, test::block_materials(false), "t");
  for (std::size_t i = 0; i < m.node_sets[0].nodes.size(); ++i) {
    const Eigen::Vector3d& p = m.nodes[m.node_sets[0].nodes[i]];
    const Eigen::Vector3d& n = m.node_sets[0].normals[i];
    EXPECT_NEAR(n.norm(), 1.0, test::kRelativeRoundoff);
    if (p.x() == 20.0 && p.y() > 0 && p.y() < 10 && p.z() > 0 && p.z() < 10) {  // inside the x = 20 face
      EXPECT_NEAR(n.x(), 1.0, test::kRelativeRoundoff);
    }
  }
}

/// The kept-order (node_order: mesh) element at each position of the rcm model, by the contract
/// of build_model: grouped by tissue, within a tissue by the lowest renumbered corner, ties in the
/// mesh's order.
std::vector<int> rcm_element_order(const Model& rcm, const Model& kept) {
  std::vector<int> new_of_mesh(rcm.mesh_node_of.size());
  for (std::size_t i = 0; i < rcm.mesh_node_of.size(); ++i) new_of_mesh[rcm.mesh_node_of[i]] = static_cast<int>(i);
  std::vector<int> order(kept.elements.size()), lowest(kept.elements.size());
  for (std::size_t e = 0; e < order.size(); ++e) {
    order[e] = static_cast<int>(e);
    lowest[e] = new_of_mesh[kept.elements[e][0]];
    for (int k = 1; k < 4; ++k) lowest[e] = std::min(lowest[e], new_of_mesh[kept.elements[e][k]]);
  }
  std::stable_sort(order.begin(), order.end(), [&](int x, int y) {
    return std::make_pair(kept.tissue_ids[x], lowest[x]) < std::make_pair(kept.tissue_ids[y], lowest[y]);
  });
  return order;
}

TEST(ModelBuilder, RcmIsTheDefaultAndKeepsTheMapBackToTheMesh) {
  EXPECT_EQ(ModelSettings{}.node_order, NodeOrder::ReverseCuthillMcKee);
  const TetMesh mesh = test::block_mesh();
  const Model rcm = test::block_model(), kept = block_in(NodeOrder::Mesh);
  ASSERT_EQ(rcm.mesh_node_of.size(), mesh.points.size());
  std::vector<int> sorted = rcm.mesh_node_of, identity(mesh.points.size());
  for (std::size_t i = 0; i < identity.size(); ++i) identity[i] = static_cast<int>(i);
  std::sort(sorted.begin(), sorted.end());
  EXPECT_EQ(sorted, identity) << "a permutation of the mesh's nodes";
  EXPECT_NE(rcm.mesh_node_of, identity);
  EXPECT_EQ(kept.mesh_node_of, identity);
  EXPECT_EQ(kept.nodes, mesh.points) << "node_order: mesh keeps the mesh's numbering";
  for (int i = 0; i < rcm.num_corner_nodes; ++i) EXPECT_EQ(rcm.nodes[i], mesh.points[rcm.mesh_node_of[i]]);
  // Same elements through the map, grouped by tissue and, within a tissue, by lowest node.
  ASSERT_EQ(rcm.elements.size(), kept.elements.size());
  const std::vector<int> order = rcm_element_order(rcm, kept);
  EXPECT_NE(order, [&] { std::vector<int> id(order.size()); std::iota(id.begin(), id.end(), 0); return id; }())
      << "the block's elements should move";
  for (std::size_t e = 0; e < rcm.elements.size(); ++e) {
    EXPECT_EQ(rcm.tissue_ids[e], kept.tissue_ids[order[e]]);
    for (int k = 0; k < 4; ++k) EXPECT_EQ(rcm.mesh_node_of[rcm.elements[e][k]], kept.elements[order[e]][k]);
  }
  EXPECT_EQ(block_in(NodeOrder::ReverseCuthillMcKee).nodes, rcm.nodes) << "deterministic";
  std::cout << "[ profile  ] block tet4: mesh order " << profile(kept) << ", rcm " << profile(rcm) << "\n";
  EXPECT_LT(profile(rcm), profile(kept));
}

TEST(ModelBuilder, RcmTet10KeepsCornersFirstAndSetsOnTheSamePoints) {
  test::BlockModelOptions o;
  o.order = ElementOrder::Quadratic;
  o.sliding_top = true;
  const Model rcm = block_in(NodeOrder::ReverseCuthillMcKee, o), kept = block_in(NodeOrder::Mesh, o);
  ASSERT_EQ(rcm.nodes.size(), kept.nodes.size());
  ASSERT_EQ(rcm.num_corner_nodes, kept.num_corner_nodes);
  // Corners first (SOFA writes only them), and the corner block is RCM on the corner graph alone.
  const std::vector<int> corner_rcm = reverse_cuthill_mckee(kept.num_corner_nodes, kept.elements, 4);
  const std::vector<int> order = rcm_element_order(rcm, kept);  // elements by tissue, then lowest node
  for (std::size_t e = 0; e < rcm.elements.size(); ++e) {
    const int k_e = order[e];
    for (int k = 0; k < 4; ++k) {
      EXPECT_LT(rcm.elements[e][k], rcm.num_corner_nodes);
      EXPECT_EQ(rcm.elements[e][k], corner_rcm[kept.elements[k_e][k]]);
    }
    for (int k = 4; k < 10; ++k) EXPECT_GE(rcm.elements[e][k], rcm.num_corner_nodes);
    EXPECT_EQ(element_volume(rcm, e), element_volume(kept, k_e)) << "element " << e;
    for (int k = 0; k < 10; ++k) EXPECT_EQ(rcm.nodes[rcm.elements[e][k]], kept.nodes[kept.elements[k_e][k]]);
  }
  // Midside nodes follow by (lower, higher) new index of their edge's ends.
  const int kEdge[6][2] = {{0, 1}, {1, 2}, {2, 0}, {0, 3}, {1, 3}, {2, 3}};
  std::vector<std::pair<int, int>> ends(rcm.nodes.size() - rcm.num_corner_nodes);
  for (const auto& el : rcm.elements)
    for (int k = 0; k < 6; ++k) ends[el[4 + k] - rcm.num_corner_nodes] = std::minmax(el[kEdge[k][0]], el[kEdge[k][1]]);
  EXPECT_TRUE(std::is_sorted(ends.begin(), ends.end()));
  EXPECT_TRUE(std::adjacent_find(ends.begin(), ends.end()) == ends.end()) << "one midside node per edge";
  // Node sets: sorted, on the same points with the same normals.
  ASSERT_EQ(rcm.node_sets.size(), 2u);
  for (std::size_t s = 0; s < rcm.node_sets.size(); ++s) {
    const NodeSet& a = rcm.node_sets[s];
    EXPECT_TRUE(std::is_sorted(a.nodes.begin(), a.nodes.end())) << a.name;
    EXPECT_EQ(a.nodes.size(), kept.node_sets[s].nodes.size()) << a.name;
    EXPECT_EQ(by_point(rcm, a), by_point(kept, kept.node_sets[s])) << a.name;
  }
  // Face sets: the same faces, their elements renumbered with the elements.
  std::vector<int> position(order.size());
  for (std::size_t e = 0; e < order.size(); ++e) position[order[e]] = static_cast<int>(e);
  ASSERT_EQ(rcm.face_sets[0].faces.size(), kept.face_sets[0].faces.size());
  for (std::size_t i = 0; i < rcm.face_sets[0].faces.size(); ++i) {
    const auto& f = kept.face_sets[0].faces[i];
    EXPECT_EQ(rcm.face_sets[0].faces[i], (std::array<int, 2>{position[f[0]], f[1]})) << "face " << i;
  }
  std::cout << "[ profile  ] block tet10: mesh order " << profile(kept) << ", rcm (corners first) " << profile(rcm)
            << "\n";
  EXPECT_LT(profile(rcm), profile(kept));
}

TEST(ModelBuilder, GravityByNameAndVector) {
  EXPECT_EQ(settings_from("gravity: {direction: supine}").gravity.acceleration(), Eigen::Vector3d(0, 9.81, 0));
  EXPECT_EQ(settings_from("gravity: {direction: none}").gravity.acceleration(), Eigen::Vector3d::Zero());
  const Eigen::Vector3d v = settings_from("gravity: {direction: [0, 0, -2], acceleration: 9810 mm/s^2}")
                                .gravity.acceleration();
  EXPECT_NEAR((v - Eigen::Vector3d(0, 0, -9.81)).norm(), 0.0, 9.81 * test::kRelativeRoundoff);
}

TEST(ModelBuilder, SettingsRoundTripThroughYaml) {
  const ModelSettings s = settings_from(R"(
units: mm-kg-s
element: tet10
node_order: mesh
node_sets:
  - {name: wall, plane: {point_mm: [0, 10, 0], normal: [0, 2, 0], tolerance_mm: 0.1}, constraint: sliding}
  - {name: corner, box_mm: [0, 0, 0, 2, 2, 2]}
face_sets:
  - {name: front, between: [[fat, fgt], outside]}
gravity: {direction: supine, acceleration: 9.8 m/s^2}
analysis: {load_steps: 4, max_load_steps: 40}
)");
  YAML::Emitter out;
  s.to_yaml(out);
  const ModelSettings again = settings_from(out.c_str());
  YAML::Emitter out2;
  again.to_yaml(out2);
  EXPECT_EQ(std::string(out.c_str()), std::string(out2.c_str()));
  EXPECT_EQ(again.element, ElementOrder::Quadratic);
  EXPECT_EQ(again.node_order, NodeOrder::Mesh);
  EXPECT_EQ(again.node_sets[0].selection.plane_normal, Eigen::Vector3d(0, 1, 0));
  EXPECT_EQ(again.face_sets[0].selection.side_a.tissues.size(), 2u);
}

// `element: auto` (the default when the key is omitted): tet10 as soon as one tissue is nearly
// incompressible (nu >= 0.49, where tet4 locks), tet4 otherwise; the choice is made per model
// from the materials of the mesh's tissues.
TEST(ModelBuilder, AutoElementIsTet10ForNearlyIncompressibleTissue) {
  const ModelSettings s = settings_from("gravity: {direction: prone, acceleration: 9.81 m/s^2}\n");
  EXPECT_FALSE(s.element.has_value());
  YAML::Emitter out;
  s.to_yaml(out);
  EXPECT_NE(std::string(out.c_str()).find("element: auto"), std::string::npos) << out.c_str();

  ModelSettings settings = test::block_settings({});
  settings.element.reset();
  std::map<std::string, MaterialSpec> materials = test::block_materials(false);
  // The fixture's tissues have K/mu >= 111 (nu >= 0.4955): auto gives tet10.
  EXPECT_EQ(build_model(test::block_mesh(), settings, materials, "test").order, ElementOrder::Quadratic);
  // Compressible enough everywhere (K = 3 mu: nu = 0.3535 < 0.49): tet4.
  for (auto& [name, m] : materials) m.K_Pa = 3.0 * m.mu_Pa;
  EXPECT_LT(materials.at("fat").poisson_ratio(), 0.49);
  EXPECT_EQ(build_model(test::block_mesh(), settings, materials, "test").order, ElementOrder::Linear);
  // One nearly incompressible tissue is enough.
  materials.at("tumor").K_Pa = 100.0 * materials.at("tumor").mu_Pa;
  EXPECT_GE(materials.at("tumor").poisson_ratio(), 0.49);
  EXPECT_EQ(build_model(test::block_mesh(), settings, materials, "test").order, ElementOrder::Quadratic);
}

TEST(ModelBuilder, SettingsErrorsNameTheKey) {
  auto error = [](const std::string& yaml) { return test::input_error_of([&] { settings_from(yaml); }); };
  EXPECT_NE(error("element: hex8").find("t.yaml: model.element: unknown element 'hex8' (tet4, tet10 or auto)"),
            std::string::npos);
  EXPECT_NE(error("unit: SI").find("model.unit"), std::string::npos);
  EXPECT_NE(error("units: cgs").find("cgs"), std::string::npos);
  EXPECT_NE(error("node_order: metis").find("t.yaml: model.node_order: unknown node order 'metis'"), std::string::npos);
  EXPECT_NE(error("node_sets: [{name: a, between: [fat, outside], box_mm: [0,0,0,1,1,1]}]").find("exactly one of"),
            std::string::npos);
  EXPECT_NE(error("node_sets: [{name: a, between: [fat, outside], constraint: glued}]").find("unknown constraint"),
            std::string::npos);
  EXPECT_NE(error("gravity: {direction: down}").find("unknown direction 'down'"), std::string::npos);
  EXPECT_NE(error("gravity: {acceleration: 9.81}").find("has no unit"), std::string::npos);
  EXPECT_NE(error("gravity: {acceleration: 9.81 kPa}").find("wrong kind of unit"), std::string::npos);
  EXPECT_NE(error("gravity: {acceleration: 9810 m/s^2}").find("check the unit"), std::string::npos);
  EXPECT_NE(error("analysis: {load_steps: 0}").find("analysis.load_steps"), std::string::npos);
  EXPECT_NE(error("node_sets: [{name: a, box_mm: [0, 0, 0, 1, 1, wide]}]").find("box_mm: expected 6 numbers"),
            std::string::npos);
}

TEST(ModelBuilder, BadSelectionsAndMissingMaterialsAreNamed) {
  auto build = [](ModelSettings s, std::map<std::string, MaterialSpec> mats) {
    return test::input_error_of([&] { build_model(test::block_mesh(), s, mats, "cfg.yaml"); });
  };
  ModelSettings s = test::block_settings({});
  auto mats = test::block_materials(false);
  ModelSettings far = s;
  far.node_sets[0].selection.plane_point_mm = {0, 50, 0};
  EXPECT_NE(build(far, mats).find("node set 'chest_wall'"), std::string::npos);
  ModelSettings unknown = s;
  unknown.node_sets[0].selection.kind = SetSelection::Kind::Between;
  unknown.node_sets[0].selection.side_a.tissues = {"muscle"};
  unknown.node_sets[0].selection.side_b.outside = true;
  EXPECT_NE(build(unknown, mats).find("unknown tissue 'muscle'"), std::string::npos);
  ModelSettings box = s;
  box.node_sets[0].selection.kind = SetSelection::Kind::Box;
  box.node_sets[0].selection.box_max_mm = {2, 2, 2};
  box.node_sets[0].constraint = Constraint::Sliding;
  EXPECT_NE(build(box, mats).find("box selection cannot slide"), std::string::npos);
  mats.erase("fgt");
  EXPECT_NE(build(s, mats).find("cfg.yaml: materials: tissue 'fgt' of the mesh has no material"), std::string::npos);
}

TEST(ModelBuilder, ValidateRefusesWhatNoWriterShouldWrite) {
  auto error = [](const Model& m) { return test::input_error_of([&] { validate_model(m); }); };
  const Model good = test::block_model();
  EXPECT_EQ(error(good), "no error");
  Model inverted = good;
  std::swap(inverted.elements[7][0], inverted.elements[7][1]);
  EXPECT_NE(error(inverted).find("element 8 (fat) is inverted"), std::string::npos);
  Model unknown = good;
  unknown.tissue_ids[3] = 9;
  EXPECT_NE(error(unknown).find("element 4 has unknown tissue id 9"), std::string::npos);
  Model orphan = good;
  orphan.nodes.emplace_back(1, 1, 1);
  orphan.num_corner_nodes += 1;
  EXPECT_NE(error(orphan).find("node 397 is used by no element"), std::string::npos);
  Model empty = good;
  empty.node_sets[0].nodes.clear();
  EXPECT_NE(error(empty).find("node set 'chest_wall'"), std::string::npos);
  Model twice = good;
  twice.face_sets[0].name = "chest_wall";
  EXPECT_NE(error(twice).find("'chest_wall' is used twice"), std::string::npos);
  Model bad_name = good;
  bad_name.tissue_names[0] = "fat tissue";
  EXPECT_NE(error(bad_name).find("'fat tissue' is not an identifier"), std::string::npos);
  Model soft = good;
  soft.materials[0].K_Pa = 0;
  EXPECT_NE(error(soft).find("tissue 'fat' (neo-hookean): bulk modulus K must be > 0"), std::string::npos);
  Model inconsistent = good;
  inconsistent.materials[1].C10_Pa *= 2;
  EXPECT_NE(error(inconsistent).find("disagrees"), std::string::npos);
}

TEST(Quantity, ParsesUnitsAndRefusesConfusions) {
  EXPECT_EQ(parse_quantity("150 Pa", Dimension::Stress, "k"), 150.0);
  EXPECT_EQ(parse_quantity(" 0.3 kPa ", Dimension::Stress, "k"), 300.0);
  EXPECT_EQ(parse_quantity("1 g/cm^3", Dimension::Density, "k"), 1000.0);
  EXPECT_NEAR(parse_quantity("1e-9 t/mm^3", Dimension::Density, "k"), 1000.0, 1000.0 * test::kRelativeRoundoff);
  EXPECT_EQ(parse_quantity("4e-5 1/Pa", Dimension::InverseStress, "k"), 4e-5);
  auto error = [](const std::string& text, Dimension d) {
    return test::input_error_of([&] { parse_quantity(text, d, "f.yaml: materials.fat.mu"); });
  };
  EXPECT_NE(error("150", Dimension::Stress).find("f.yaml: materials.fat.mu: '150' has no unit"), std::string::npos);
  EXPECT_NE(error("150 kg/m^3", Dimension::Stress).find("wrong kind of unit"), std::string::npos);
  EXPECT_NE(error("150 psi", Dimension::Stress).find("unknown unit 'psi'"), std::string::npos);
  EXPECT_NE(error("soft", Dimension::Stress).find("not a quantity"), std::string::npos);
  for (double v : {150.0, 9.81, 1e-6, 0.1 + 0.2, 50e3})
    EXPECT_EQ(parse_quantity(format_quantity(v, Dimension::Stress), Dimension::Stress, "k"), v);
}

TEST(ModelBuilder, Tet10InterfaceSetsTakeOnlyTheMidsidesOfTheirTriangles) {
  // Kuhn diagonals at the box's edges join two boundary nodes through the interior (e.g.
  // (18,0,0)-(20,2,2)): their midside nodes must not join an interface set.
  ModelSettings s = test::block_settings({});
  s.element = ElementOrder::Quadratic;
  s.node_sets[0].selection.kind = SetSelection::Kind::Between;
  s.node_sets[0].selection.side_a.tissues = {"tumor"};
  s.node_sets[0].selection.side_b.outside = true;
  const Model m = build_model(test::block_mesh(), s, test::block_materials(false), "t");
  auto on_boundary = [](const Eigen::Vector3d& p) {
    return p.x() == 20.0 || p.y() == 0.0 || p.y() == 10.0 || p.z() == 0.0 || p.z() == 10.0;
  };
  int midsides = 0;
  for (int v : m.node_sets[0].nodes) {
    EXPECT_TRUE(on_boundary(m.nodes[v])) << "node at (" << m.nodes[v].transpose() << ")";
    midsides += v >= m.num_corner_nodes;
  }
  EXPECT_GT(midsides, 0);
}
