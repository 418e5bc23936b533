// FEBio writer: the .feb is read back with VTK's XML parser (expat; independent of the writer) and
// checked against the FEBio 4.0 format rules (FEBio User's Manual, version 4, "The FEBio Input
// File"; docs/formats.md, "FEBio") and against the Model; plus the acceptance test that FEBio
// Mooney-Rivlin (c2 = 0, Abaqus pressure) and Abaqus NEO HOOKE are one energy.
#include "fe_export/abaqus/write_abaqus.h"
#include "fe_export/febio/write_febio.h"
#include "materials/make_law.h"
#include "support/model_fixture.h"
#include "support/tolerances.h"

#include "core/errors.h"

#include <gtest/gtest.h>
#include <vtkNew.h>
#include <vtkXMLDataElement.h>
#include <vtkXMLDataParser.h>

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cctype>
#include <map>
#include <memory>
#include <random>
#include <set>
#include <sstream>

namespace tissuemesh {
namespace {

using test::BlockModelOptions;
using test::block_model;
using test::kRelativeRoundoff;

// ----------------------------------------------------------------------------------------------
// Reading the XML back

struct Feb {
  std::string text;
  std::vector<std::string> notes;
  vtkNew<vtkXMLDataParser> parser;
  vtkXMLDataElement* root = nullptr;
};

std::unique_ptr<Feb> write_and_parse(const Model& model, const FebioOptions& options = {}) {
  auto feb = std::make_unique<Feb>();
  std::ostringstream out;
  feb->notes = write_febio(model, out, options);
  feb->text = out.str();
  std::istringstream in(feb->text);
  feb->parser->SetStream(&in);
  feb->parser->SetIgnoreCharacterData(0);
  EXPECT_EQ(feb->parser->Parse(), 1) << "the .feb is not well-formed XML";
  feb->root = feb->parser->GetRootElement();
  EXPECT_NE(feb->root, nullptr);
  return feb;
}

std::vector<vtkXMLDataElement*> kids(vtkXMLDataElement* e, const std::string& name = "") {
  std::vector<vtkXMLDataElement*> out;
  for (int i = 0; i < e->GetNumberOfNestedElements(); ++i)
    if (name.empty() || name == e->GetNestedElement(i)->GetName()) out.push_back(e->GetNestedElement(i));
  return out;
}

vtkXMLDataElement* kid(vtkXMLDataElement* e, const std::string& name) {
  const auto all = kids(e, name);
  EXPECT_EQ(all.size(), 1u) << "expected one <" << name << "> in <" << e->GetName() << ">";
  return all.empty() ? nullptr : all[0];
}

std::string attr(vtkXMLDataElement* e, const char* name) {
  const char* v = e->GetAttribute(name);
  return v ? v : "";
}

std::string text(vtkXMLDataElement* e) {
  std::string s = e->GetCharacterData() ? e->GetCharacterData() : "";
  const auto b = s.find_first_not_of(" \t\r\n"), l = s.find_last_not_of(" \t\r\n");
  return b == std::string::npos ? "" : s.substr(b, l - b + 1);
}

double number(vtkXMLDataElement* e) { return std::strtod(text(e).c_str(), nullptr); }
std::vector<double> numbers(const std::string& s) {
  std::vector<double> out;
  std::string item;
  std::istringstream in(s);
  while (std::getline(in, item, ','))
    if (item.find_first_not_of(" \t\r\n") != std::string::npos) out.push_back(std::strtod(item.c_str(), nullptr));
  return out;
}

std::vector<int> ints(const std::string& s) {
  std::vector<int> out;
  for (double v : numbers(s)) out.push_back(static_cast<int>(v));
  return out;
}
vtkXMLDataElement* section(const Feb& f, const std::string& name) { return kid(f.root, name); }

/// Model elements grouped by tissue in model order: the documented .feb numbering.
std::vector<int> expected_element_ids(const Model& m) {
  std::vector<int> order(m.elements.size()), ids(m.elements.size());
  for (std::size_t e = 0; e < order.size(); ++e) order[e] = static_cast<int>(e);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return m.tissue_ids[a] < m.tissue_ids[b]; });
  for (std::size_t k = 0; k < order.size(); ++k) ids[order[k]] = static_cast<int>(k) + 1;
  return ids;
}

/// The block model with its elements reordered so that the tissues interleave.
Model interleaved(Model m) {
  std::vector<int> perm(m.elements.size());
  for (std::size_t i = 0; i < perm.size(); ++i) perm[i] = static_cast<int>(i);
  std::mt19937 rng(7);
  std::shuffle(perm.begin(), perm.end(), rng);
  auto elements = m.elements;
  auto tissues = m.tissue_ids;
  for (std::size_t i = 0; i < perm.size(); ++i) m.elements[i] = elements[perm[i]], m.tissue_ids[i] = tissues[perm[i]];
  m.face_sets.clear();  // face sets refer to element indices
  return m;
}

// ----------------------------------------------------------------------------------------------

TEST(FebioExport, RootModuleAndSectionOrder) {
  const auto f = write_and_parse(block_model());
  EXPECT_EQ(f->text.rfind("<?xml version=\"1.0\" encoding=\"ISO-8859-1\"?>\n", 0), 0u);
  EXPECT_STREQ(f->root->GetName(), "febio_spec");
  EXPECT_EQ(attr(f->root, "version"), "4.0");
  std::vector<std::string> names;
  for (auto* s : kids(f->root)) names.push_back(s->GetName());
  const std::vector<std::string> order{"Module", "Control", "Material", "Mesh", "MeshDomains",
                                       "Boundary", "Loads", "LoadData", "Output"};
  EXPECT_EQ(names, order);  // FEBio User's Manual 4, "The FEBio Input File"; Module first
  EXPECT_EQ(attr(f->root->GetNestedElement(0), "type"), "solid");
}

TEST(FebioExport, ControlFollowsAnalysisSettings) {
  Model m = block_model();
  m.analysis.load_steps = 8;
  m.analysis.min_step_fraction = 1e-3;
  m.analysis.max_newton_iterations = 30;
  m.analysis.displacement_tolerance = 2e-3;
  m.analysis.energy_tolerance = 3e-2;
  m.analysis.residual_tolerance = 4e-6;
  const auto f = write_and_parse(m);
  auto* c = section(*f, "Control");
  EXPECT_EQ(text(kid(c, "analysis")), "STATIC");
  EXPECT_EQ(number(kid(c, "time_steps")), 8);
  EXPECT_EQ(number(kid(c, "step_size")), 1.0 / 8);
  auto* ts = kid(c, "time_stepper");
  EXPECT_EQ(attr(ts, "type"), "default");
  EXPECT_EQ(number(kid(ts, "max_retries")), 5);
  EXPECT_EQ(number(kid(ts, "opt_iter")), 10);
  EXPECT_EQ(number(kid(ts, "dtmin")), 1e-3);
  EXPECT_EQ(number(kid(ts, "dtmax")), 1.0 / 8);
  auto* s = kid(c, "solver");
  EXPECT_EQ(attr(s, "type"), "solid");
  EXPECT_EQ(text(kid(s, "symmetric_stiffness")), "symmetric");
  EXPECT_EQ(number(kid(s, "dtol")), 2e-3);
  EXPECT_EQ(number(kid(s, "etol")), 3e-2);
  EXPECT_EQ(number(kid(s, "rtol")), 4e-6);
  EXPECT_EQ(number(kid(s, "max_refs")), 30);
  auto* qn = kid(s, "qn_method");
  EXPECT_EQ(attr(qn, "type"), "BFGS");
  EXPECT_EQ(number(kid(qn, "max_ups")), 0);  // full Newton
  EXPECT_TRUE(kids(s, "linear_solver").empty());  // FEBio's build default
  const auto g = write_and_parse(m, FebioOptions{"skyline"});
  EXPECT_EQ(attr(kid(kid(section(*g, "Control"), "solver"), "linear_solver"), "type"), "skyline");
}

class FebioMesh : public ::testing::TestWithParam<ElementOrder> {};

TEST_P(FebioMesh, NodeIdsIncreaseAndCoordinatesRoundTrip) {
  for (UnitSystem u : {UnitSystem::MillimetreTonneSecond, UnitSystem::SI}) {
    BlockModelOptions o;
    o.order = GetParam();
    o.units = u;
    const Model m = block_model(o);
    const auto f = write_and_parse(m);
    auto* nodes = kid(section(*f, "Mesh"), "Nodes");
    EXPECT_EQ(attr(nodes, "name"), "all");
    const auto all = kids(nodes);
    ASSERT_EQ(all.size(), m.nodes.size());
    for (std::size_t i = 0; i < all.size(); ++i) {
      ASSERT_STREQ(all[i]->GetName(), "node");
      ASSERT_EQ(std::stoi(attr(all[i], "id")), static_cast<int>(i) + 1);  // 1..N, strictly increasing
      const auto x = numbers(text(all[i]));
      ASSERT_EQ(x.size(), 3u);
      for (int k = 0; k < 3; ++k) ASSERT_EQ(x[k], length_from_mm(u, m.nodes[i][k])) << "node " << i + 1;
    }
  }
}

TEST_P(FebioMesh, OneElementBlockPerTissueWithIncreasingIds) {
  BlockModelOptions o;
  o.order = GetParam();
  for (const Model& m : {block_model(o), interleaved(block_model(o))}) {
    const auto f = write_and_parse(m);
    const auto expected = expected_element_ids(m);
    EXPECT_EQ(febio_element_ids(m), expected);
    std::vector<int> model_of(m.elements.size() + 1, -1);
    for (std::size_t e = 0; e < expected.size(); ++e) model_of[expected[e]] = static_cast<int>(e);
    const auto blocks = kids(section(*f, "Mesh"), "Elements");
    ASSERT_EQ(blocks.size(), m.tissue_names.size());
    int last = 0;
    std::size_t count = 0;
    for (std::size_t t = 0; t < blocks.size(); ++t) {
      EXPECT_EQ(attr(blocks[t], "name"), m.tissue_names[t]);
      EXPECT_EQ(attr(blocks[t], "type"), GetParam() == ElementOrder::Linear ? "tet4" : "tet10");
      for (auto* el : kids(blocks[t])) {
        const int id = std::stoi(attr(el, "id"));
        ASSERT_GT(id, last) << "ids must increase within a block and across the file";
        last = id;
        ++count;
        const int e = model_of.at(id);
        ASSERT_GE(e, 0);
        EXPECT_EQ(m.tissue_ids[e], static_cast<int>(t) + 1);
        const auto conn = ints(text(el));
        ASSERT_EQ(static_cast<int>(conn.size()), m.nodes_per_element());
        for (int k = 0; k < m.nodes_per_element(); ++k) ASSERT_EQ(conn[k], m.elements[e][k] + 1);
      }
    }
    EXPECT_EQ(count, m.elements.size());
    EXPECT_EQ(last, static_cast<int>(m.elements.size()));
  }
}

TEST_P(FebioMesh, SurfacesAreTheFaceSets) {
  BlockModelOptions o;
  o.order = GetParam();
  const Model m = block_model(o);
  const auto f = write_and_parse(m);
  const auto surfaces = kids(section(*f, "Mesh"), "Surface");
  ASSERT_EQ(surfaces.size(), m.face_sets.size());
  const FaceSet& skin = m.face_sets[0];
  EXPECT_EQ(attr(surfaces[0], "name"), skin.name);
  const auto faces = kids(surfaces[0]);
  ASSERT_EQ(faces.size(), skin.faces.size());
  for (std::size_t i = 0; i < faces.size(); ++i) {
    EXPECT_STREQ(faces[i]->GetName(), GetParam() == ElementOrder::Linear ? "tri3" : "tri6");
    const auto& [e, face] = skin.faces[i];
    std::vector<int> want;
    for (int c : face_corners(face)) want.push_back(m.elements[e][c] + 1);
    if (GetParam() == ElementOrder::Quadratic)
      for (int c : face_midsides(face)) want.push_back(m.elements[e][c] + 1);
    EXPECT_EQ(ints(text(faces[i])), want);
  }
}

INSTANTIATE_TEST_SUITE_P(Orders, FebioMesh, ::testing::Values(ElementOrder::Linear, ElementOrder::Quadratic));

TEST(FebioExport, DomainsReferenceElementBlocksAndMaterials) {
  const auto f = write_and_parse(block_model());
  std::set<std::string> blocks, materials;
  for (auto* b : kids(section(*f, "Mesh"), "Elements")) blocks.insert(attr(b, "name"));
  for (auto* mat : kids(section(*f, "Material"), "material")) materials.insert(attr(mat, "name"));
  const auto domains = kids(section(*f, "MeshDomains"));
  EXPECT_EQ(domains.size(), blocks.size());
  for (auto* d : domains) {
    EXPECT_STREQ(d->GetName(), "SolidDomain");
    EXPECT_TRUE(blocks.count(attr(d, "name"))) << attr(d, "name");
    EXPECT_TRUE(materials.count(attr(d, "mat"))) << attr(d, "mat");
  }
}

TEST(FebioExport, MaterialParametersAreValidForTheirType) {
  Model m = block_model(BlockModelOptions{ElementOrder::Linear, true});  // tumor Ogden
  MaterialSpec cnh = m.materials[1];
  cnh.law = MaterialLaw::CompressibleNeoHookean;
  m.materials[1] = cnh;  // fgt as FEBio neo-Hookean
  const auto f = write_and_parse(m);
  const std::map<std::string, std::set<std::string>> allowed{
      {"neo-Hookean", {"density", "E", "v"}},
      {"Mooney-Rivlin", {"density", "c1", "c2", "k", "pressure_model"}},
      {"Ogden", {"density", "c1", "c2", "c3", "c4", "c5", "c6", "m1", "m2", "m3", "m4", "m5", "m6", "k",
                 "pressure_model"}}};  // FEBio User's Manual 4, "Materials"
  const auto mats = kids(section(*f, "Material"), "material");
  ASSERT_EQ(mats.size(), 3u);
  const UnitSystem u = m.units;
  for (std::size_t t = 0; t < mats.size(); ++t) {
    auto* mat = mats[t];
    const MaterialSpec& s = m.materials[t];
    EXPECT_EQ(attr(mat, "id"), std::to_string(t + 1));
    EXPECT_EQ(attr(mat, "name"), m.tissue_names[t]);
    const std::string type = attr(mat, "type");
    ASSERT_TRUE(allowed.count(type)) << type;
    std::map<std::string, vtkXMLDataElement*> p;
    for (auto* q : kids(mat)) {
      EXPECT_TRUE(allowed.at(type).count(q->GetName())) << type << " has no parameter " << q->GetName();
      p[q->GetName()] = q;
    }
    EXPECT_EQ(number(p.at("density")), density_from_kg_per_m3(u, s.density_kg_m3));
    if (type != "neo-Hookean") {  // uncoupled: k must be set (default 0) and the Abaqus U(J)
      EXPECT_GT(number(p.at("k")), 0.0);
      EXPECT_EQ(number(p.at("k")), stress_from_pascal(u, s.K_Pa));
      EXPECT_EQ(text(p.at("pressure_model")), "Abaqus");
    }
    if (t == 0) {
      EXPECT_EQ(type, "Mooney-Rivlin");  // fat: NeoHookean
      EXPECT_EQ(number(p.at("c1")), stress_from_pascal(u, s.C10_Pa));
      EXPECT_EQ(number(p.at("c2")), 0.0);
    } else if (t == 1) {
      EXPECT_EQ(type, "neo-Hookean");
      EXPECT_EQ(number(p.at("E")), stress_from_pascal(u, s.young_modulus_Pa()));
      EXPECT_EQ(number(p.at("v")), s.poisson_ratio());
    } else {
      EXPECT_EQ(type, "Ogden");
      for (std::size_t i = 0; i < s.ogden.size(); ++i) {
        EXPECT_EQ(number(p.at("c" + std::to_string(i + 1))), stress_from_pascal(u, 2.0 * s.ogden[i].mu_Pa));
        EXPECT_EQ(number(p.at("m" + std::to_string(i + 1))), s.ogden[i].alpha);
      }
    }
  }
  EXPECT_NE(f->text.find("source: test fixture"), std::string::npos) << "a comment per material with its source";
}

/// body_load components as read from the file.
Eigen::Vector3d body_load(const Feb& f) {
  auto* bl = kid(section(f, "Loads"), "body_load");
  EXPECT_EQ(attr(bl, "type"), "const");
  Eigen::Vector3d v;
  const char* axes[3] = {"x", "y", "z"};
  for (int i = 0; i < 3; ++i) v[i] = number(kid(bl, axes[i]));
  return v;
}

TEST(FebioExport, GravityIsEnteredWithFebiosSign) {
  // docs/formats.md, "FEBio": the const body load is minus the acceleration; prone gravity (0,
  // -9.81, 0) m/s^2 in mm-t-s is (0, -9810, 0) mm/s^2, so the file holds y = +9810.
  Model m = block_model();
  ASSERT_EQ(m.gravity.acceleration_m_s2, Eigen::Vector3d(0, -9.81, 0));
  const auto f = write_and_parse(m);
  const Eigen::Vector3d v = body_load(*f);
  EXPECT_EQ(v[0], 0.0);
  EXPECT_NEAR(v[1], 9810.0, 9810.0 * kRelativeRoundoff);
  EXPECT_EQ(v[2], 0.0);
  m.gravity.acceleration_m_s2 = Eigen::Vector3d(1.0, 9.81, -2.0);
  m.units = UnitSystem::SI;
  const Eigen::Vector3d w = body_load(*write_and_parse(m));
  EXPECT_NEAR((w - Eigen::Vector3d(-1.0, -9.81, 2.0)).norm(), 0.0, 10 * kRelativeRoundoff);
}

TEST(FebioExport, LoadCurveReferencesAndOutput) {
  Model m = block_model();
  m.title = "breast_01";
  const auto f = write_and_parse(m);
  std::set<std::string> controllers;
  for (auto* lc : kids(section(*f, "LoadData"), "load_controller")) {
    controllers.insert(attr(lc, "id"));
    EXPECT_EQ(attr(lc, "type"), "loadcurve");
    EXPECT_EQ(text(kid(lc, "interpolate")), "LINEAR");
    std::vector<double> pts;
    for (auto* pt : kids(kid(lc, "points"))) {
      const auto xy = numbers(text(pt));
      pts.insert(pts.end(), xy.begin(), xy.end());
    }
    EXPECT_EQ(pts, (std::vector<double>{0, 0, 1, 1}));
  }
  for (auto* c : kids(kid(section(*f, "Loads"), "body_load"))) EXPECT_TRUE(controllers.count(attr(c, "lc")));
  auto* out = section(*f, "Output");
  auto* plot = kid(out, "plotfile");
  EXPECT_EQ(attr(plot, "type"), "febio");
  std::set<std::string> vars;
  for (auto* v : kids(plot, "var")) vars.insert(attr(v, "type"));
  EXPECT_EQ(vars, (std::set<std::string>{"displacement", "stress"}));
  auto* nd = kid(kid(out, "logfile"), "node_data");
  EXPECT_EQ(attr(nd, "data"), "ux;uy;uz");
  EXPECT_EQ(attr(nd, "file"), "breast_01_disp.txt");
  EXPECT_EQ(attr(nd, "delim"), ",");
}

/// Node sets by name as read from the file (0-based).
std::map<std::string, std::vector<int>> node_sets(const Feb& f) {
  std::map<std::string, std::vector<int>> sets;
  for (auto* s : kids(section(f, "Mesh"), "NodeSet")) {
    EXPECT_EQ(sets.count(attr(s, "name")), 0u);
    for (int id : ints(text(s))) sets[attr(s, "name")].push_back(id - 1);
  }
  return sets;
}

TEST(FebioExport, FixedAndAxisSlidingSetsAreZeroDisplacementOnNodeSets) {
  const Model m = block_model(BlockModelOptions{ElementOrder::Linear, false, true});  // top: normal +z
  const auto f = write_and_parse(m);
  const auto sets = node_sets(*f);
  for (const NodeSet& s : m.node_sets) EXPECT_EQ(sets.at(s.name), s.nodes) << s.name;
  const auto bcs = kids(section(*f, "Boundary"), "bc");
  ASSERT_EQ(bcs.size(), 2u);
  for (auto* bc : bcs) {
    EXPECT_EQ(attr(bc, "type"), "zero displacement");
    ASSERT_TRUE(sets.count(attr(bc, "node_set"))) << "bc references a missing NodeSet";
    const bool fixed = attr(bc, "node_set") == "chest_wall";
    EXPECT_EQ(number(kid(bc, "x_dof")), fixed ? 1 : 0);
    EXPECT_EQ(number(kid(bc, "y_dof")), fixed ? 1 : 0);
    EXPECT_EQ(number(kid(bc, "z_dof")), 1);
  }
}

TEST(FebioExport, ObliqueSlidingSetsAreLinearConstraintsSpanningTheNormals) {
  Model m = block_model(BlockModelOptions{ElementOrder::Linear, false, true});
  NodeSet side;  // plane x = 20 with a tilted normal; shares nodes with top and chest_wall
  side.name = "side";
  side.constraint = Constraint::Sliding;
  side.selection = "test";
  for (std::size_t i = 0; i < m.nodes.size(); ++i)
    if (m.nodes[i].x() == 20.0) side.nodes.push_back(static_cast<int>(i)), side.normals.emplace_back(0.8, 0.0, 0.6);
  m.node_sets.push_back(side);
  for (bool oblique_top : {false, true}) {
    if (oblique_top)  // then the top/side edge has two oblique normals
      for (auto& n : m.node_sets[1].normals) n = Eigen::Vector3d(0.0, 0.6, 0.8);
    const auto f = write_and_parse(m);
    const auto sets = node_sets(*f);
    const char* dofs = "xyz";
    std::map<int, std::vector<Eigen::Vector3d>> constraints;  // per node: rows c with c.u = 0
    std::set<std::pair<int, int>> parents, children, fixed_dofs;
    for (auto* bc : kids(section(*f, "Boundary"), "bc")) {
      if (attr(bc, "type") == "zero displacement") {
        for (int i = 0; i < 3; ++i)
          if (number(kid(bc, std::string(1, dofs[i]) + "_dof")) == 1)
            for (int v : sets.at(attr(bc, "node_set"))) {
              constraints[v].push_back(Eigen::Vector3d::Unit(i));
              fixed_dofs.insert({v, i});
            }
        continue;
      }
      ASSERT_EQ(attr(bc, "type"), "linear constraint");
      const int node = static_cast<int>(number(kid(bc, "node"))) - 1;
      const int parent = static_cast<int>(std::string(dofs).find(text(kid(bc, "dof"))));
      Eigen::Vector3d c = Eigen::Vector3d::Unit(parent);  // u_p - sum value u_child = 0
      EXPECT_TRUE(parents.insert({node, parent}).second) << "dof is parent twice";
      for (auto* ch : kids(bc, "child_dof")) {
        EXPECT_EQ(number(kid(ch, "node")) - 1, node);
        const int d = static_cast<int>(std::string(dofs).find(text(kid(ch, "dof"))));
        c[d] -= number(kid(ch, "value"));
        children.insert({node, d});
      }
      constraints[node].push_back(c);
    }
    for (const auto& p : parents) {  // FELinearConstraintManager::Activate refuses these
      EXPECT_FALSE(children.count(p)) << "parent dof is also a child dof";
      EXPECT_FALSE(fixed_dofs.count(p)) << "parent dof is also fixed";
    }
    std::map<int, std::vector<Eigen::Vector3d>> wanted;  // what the model asks per node
    for (const NodeSet& s : m.node_sets)
      for (std::size_t k = 0; k < s.nodes.size(); ++k)
        if (s.constraint == Constraint::Fixed)
          for (int i = 0; i < 3; ++i) wanted[s.nodes[k]].push_back(Eigen::Vector3d::Unit(i));
        else wanted[s.nodes[k]].push_back(s.normals[k]);
    std::set<int> nodes;
    for (const auto& [v, rows] : wanted) nodes.insert(v);
    for (const auto& [v, rows] : constraints) nodes.insert(v);
    auto rank = [](const std::vector<Eigen::Vector3d>& rows) {
      Eigen::MatrixXd a(rows.size(), 3);
      for (std::size_t r = 0; r < rows.size(); ++r) a.row(r) = rows[r].transpose();
      Eigen::FullPivLU<Eigen::MatrixXd> lu(a);
      lu.setThreshold(1e-9);
      return rows.empty() ? 0 : static_cast<int>(lu.rank());
    };
    for (int v : nodes) {  // same constrained subspace: rank(C) = rank(N) = rank([C; N])
      auto c = constraints[v], n = wanted[v];
      auto both = c;
      both.insert(both.end(), n.begin(), n.end());
      EXPECT_EQ(rank(c), rank(n)) << "node " << v + 1;
      EXPECT_EQ(rank(both), rank(n)) << "node " << v + 1;
    }
  }
}

TEST(FebioExport, RefusesNamesFebioCannotRead) {
  Model m = block_model(), n = block_model();
  m.node_sets[0].name = "all";     // the Nodes block's set
  n.tissue_names[0].assign(128, 'f');  // XMLReader attribute buffers hold 127 characters
  std::ostringstream out;
  EXPECT_THROW(write_febio(m, out, {}), InputError);
  EXPECT_THROW(write_febio(n, out, {}), InputError);
}

TEST(FebioExport, EscapesNamesAndCommentsAndIsDeterministic) {
  Model m = block_model();
  m.title = "caf\xC3\xA9 <&> \"q\" -- x-";
  m.materials[0].source = "Smith -- 2010 <table 2> & caf\xC3\xA9-";
  const auto f = write_and_parse(m);  // well-formed despite markup, "--" and UTF-8 in the inputs
  EXPECT_EQ(attr(kid(kid(section(*f, "Output"), "logfile"), "node_data"), "file"), "caf________q__--_x-_disp.txt");
  std::ostringstream again;
  write_febio(m, again, {});
  EXPECT_EQ(again.str(), f->text);
  m.title.assign(300, 't');
  EXPECT_LT(attr(kid(kid(section(*write_and_parse(m), "Output"), "logfile"), "node_data"), "file").size(), 128u);
}

TEST(FebioExport, NotesWarnAboutTet4Locking) {
  const auto lin = write_and_parse(block_model());
  const auto has = [](const std::vector<std::string>& notes, const std::string& what) {
    return std::any_of(notes.begin(), notes.end(), [&](const std::string& n) { return n.find(what) != std::string::npos; });
  };
  EXPECT_TRUE(has(lin->notes, "locks"));  // K/mu up to 333 in the fixture
  BlockModelOptions quad;
  quad.order = ElementOrder::Quadratic;
  EXPECT_FALSE(has(write_and_parse(block_model(quad))->notes, "locks"));
  EXPECT_TRUE(has(write_and_parse(interleaved(block_model()))->notes, "febio_element_ids"));
}

// ----------------------------------------------------------------------------------------------
// Acceptance: the same tissue written as FEBio Mooney-Rivlin (c2 = 0, pressure_model Abaqus) and as
// Abaqus NEO HOOKE has identical energy at sample deformations.

struct Invariants {
  double J, I1bar, I2bar;
};

Invariants invariants(const Eigen::Matrix3d& F) {
  const Eigen::Matrix3d C = F.transpose() * F;
  const double J = F.determinant(), I1 = C.trace(), I2 = 0.5 * (I1 * I1 - (C * C).trace());
  return {J, std::pow(J, -2.0 / 3.0) * I1, std::pow(J, -4.0 / 3.0) * I2};
}

/// FEBio Mooney-Rivlin with pressure_model Abaqus (FEMooneyRivlin + FEUncoupledMaterial U(J)).
double febio_mooney_rivlin(double c1, double c2, double k, const Eigen::Matrix3d& F) {
  const Invariants i = invariants(F);
  return c1 * (i.I1bar - 3) + c2 * (i.I2bar - 3) + 0.5 * k * (i.J - 1) * (i.J - 1);
}

/// Abaqus/CalculiX *HYPERELASTIC, NEO HOOKE: U = C10 (I1bar - 3) + (J - 1)^2 / D1.
double abaqus_neo_hooke(double C10, double D1, const Eigen::Matrix3d& F) {
  const Invariants i = invariants(F);
  return C10 * (i.I1bar - 3) + (i.J - 1) * (i.J - 1) / D1;
}

/// C10 and D1 from the data line after "*HYPERELASTIC, NEO HOOKE" (comment lines "**" skipped).
std::pair<double, double> read_neo_hooke(const std::string& inp) {
  std::istringstream in(inp);
  std::string line;
  bool found = false;
  while (std::getline(in, line)) {
    std::string upper = line;
    std::transform(upper.begin(), upper.end(), upper.begin(), [](unsigned char c) { return std::toupper(c); });
    upper.erase(std::remove(upper.begin(), upper.end(), ' '), upper.end());
    if (found && line.rfind("**", 0) != 0) {
      const auto v = numbers(line);
      EXPECT_GE(v.size(), 2u) << line;
      return v.size() >= 2 ? std::make_pair(v[0], v[1]) : std::make_pair(0.0, 0.0);
    }
    if (upper.rfind("*HYPERELASTIC", 0) == 0) {
      EXPECT_NE(upper.find("NEOHOOKE"), std::string::npos) << line;
      found = true;
    }
  }
  ADD_FAILURE() << "no *HYPERELASTIC, NEO HOOKE in the .inp";
  return {0.0, 0.0};
}

TEST(FebioAbaqusAcceptance, MooneyRivlinC2ZeroAndNeoHookeHaveTheSameEnergy) {
  Model m = block_model();
  const MaterialSpec spec = m.materials[0];  // neo-Hookean fat: C10 75 Pa, K 50 kPa
  ASSERT_EQ(spec.law, MaterialLaw::NeoHookean);
  m.tissue_names = {"breast"};
  m.materials = {spec};
  std::fill(m.tissue_ids.begin(), m.tissue_ids.end(), 1);

  const auto f = write_and_parse(m);
  const auto mats = kids(section(*f, "Material"), "material");
  ASSERT_EQ(mats.size(), 1u);
  ASSERT_EQ(attr(mats[0], "type"), "Mooney-Rivlin");
  ASSERT_EQ(text(kid(mats[0], "pressure_model")), "Abaqus");
  const double c1 = number(kid(mats[0], "c1")), c2 = number(kid(mats[0], "c2")), k = number(kid(mats[0], "k"));
  EXPECT_EQ(c2, 0.0);

  std::ostringstream inp;
  write_abaqus(m, inp, {});
  const auto [C10, D1] = read_neo_hooke(inp.str());
  const auto law = make_law(spec, UnitSystem::MillimetreTonneSecond);

  std::vector<std::pair<std::string, Eigen::Matrix3d>> samples;
  samples.emplace_back("uniaxial 1.3", Eigen::Vector3d(1.3, 1 / std::sqrt(1.25), 1 / std::sqrt(1.25)).asDiagonal());
  Eigen::Matrix3d shear = Eigen::Matrix3d::Identity();
  shear(0, 1) = 0.4;
  samples.emplace_back("simple shear 0.4", shear);
  samples.emplace_back("volumetric J = 1.05^3", 1.05 * Eigen::Matrix3d::Identity());
  samples.emplace_back("compression 0.7", Eigen::Vector3d(0.7, 1.1, 1.2).asDiagonal());
  std::mt19937 rng(42);
  std::uniform_real_distribution<double> d(-0.3, 0.3);
  while (samples.size() < 10) {
    Eigen::Matrix3d F = Eigen::Matrix3d::Identity();
    for (int i = 0; i < 9; ++i) F(i / 3, i % 3) += d(rng);
    if (F.determinant() > 0.2) samples.emplace_back("random " + std::to_string(samples.size()), F);
  }
  for (const auto& [name, F] : samples) {
    const double wf = febio_mooney_rivlin(c1, c2, k, F);
    const double wa = abaqus_neo_hooke(C10, D1, F);
    const double wl = law->energy(F.transpose() * F);
    ASSERT_GT(wf, 0.0) << name;
    EXPECT_NEAR(wf, wa, kRelativeRoundoff * wf) << name;
    EXPECT_NEAR(wf, wl, kRelativeRoundoff * wf) << name;
  }
}

}  // namespace
}  // namespace tissuemesh
