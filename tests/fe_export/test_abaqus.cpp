// write_abaqus read back by a small independent .inp reader (docs/formats.md, "Abaqus / CalculiX"):
// the mesh, the sets, the materials and the step must be what the Model says, in CalculiX's syntax
// limits.
#include "fe_export/abaqus/write_abaqus.h"

#include "core/errors.h"
#include "support/model_fixture.h"
#include "support/tolerances.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <map>
#include <set>
#include <sstream>

namespace tissuemesh {
namespace {

std::string upper(std::string s) {
  for (char& c : s) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return s;
}

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t"), e = s.find_last_not_of(" \t\r");
  return b == std::string::npos ? "" : s.substr(b, e - b + 1);
}

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> out;
  std::stringstream in(line);
  for (std::string item; std::getline(in, item, ',');) out.push_back(trim(item));
  return out;
}

double number(const std::string& s) {
  std::size_t used = 0;
  const double v = std::stod(s, &used);
  EXPECT_EQ(used, s.size()) << "not a number: '" << s << "'";
  return v;
}

int integer(const std::string& s) {
  std::size_t used = 0;
  const int v = std::stoi(s, &used);
  EXPECT_EQ(used, s.size()) << "not an integer: '" << s << "'";
  return v;
}

/// One keyword card: "*ELEMENT, TYPE=C3D4, ELSET=FAT" -> name ELEMENT, params, data lines.
struct Card {
  std::string name;
  std::map<std::string, std::string> params;  // upper-case keys; flags map to ""
  std::vector<std::vector<std::string>> data;
  std::string param(const std::string& key) const {
    auto it = params.find(key);
    return it == params.end() ? "" : it->second;
  }
};

/// The deck as cards plus the mesh and sets it defines. Continuation-free: every data line is
/// complete (what write_abaqus promises); the 16-entry rule is checked per line.
struct Inp {
  std::vector<Card> cards;
  std::map<int, Eigen::Vector3d> nodes;
  std::map<int, std::vector<int>> elements;
  std::map<int, std::string> element_type;
  std::map<std::string, std::vector<std::string>> elsets;  // members: ids or set names
  std::map<std::string, std::vector<int>> nsets;
  std::size_t max_entries = 0;
  std::size_t longest_real = 0;  // characters of the longest real field (CalculiX reads 20)

  std::vector<const Card*> all(const std::string& name) const {
    std::vector<const Card*> out;
    for (const Card& c : cards)
      if (c.name == name) out.push_back(&c);
    return out;
  }
  std::size_t index(const std::string& name) const {
    for (std::size_t i = 0; i < cards.size(); ++i)
      if (cards[i].name == name) return i;
    return cards.size();
  }
  /// Element ids of a set, nested set names expanded.
  std::set<int> element_ids(const std::string& set) const {
    std::set<int> ids;
    for (const std::string& m : elsets.at(set)) {
      if (std::isdigit(static_cast<unsigned char>(m[0]))) {
        ids.insert(integer(m));
      } else {
        const std::set<int> inner = element_ids(m);
        ids.insert(inner.begin(), inner.end());
      }
    }
    return ids;
  }
};

Inp read_inp(const std::string& text) {
  Inp inp;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("**", 0) == 0 || trim(line).empty()) continue;
    if (line[0] == '*') {
      Card c;
      const std::vector<std::string> parts = split(line.substr(1));
      c.name = upper(parts[0]);
      for (std::size_t i = 1; i < parts.size(); ++i) {
        const auto eq = parts[i].find('=');
        if (eq == std::string::npos)
          c.params[upper(parts[i])] = "";
        else
          c.params[upper(trim(parts[i].substr(0, eq)))] = trim(parts[i].substr(eq + 1));
      }
      inp.cards.push_back(c);
      continue;
    }
    EXPECT_FALSE(inp.cards.empty()) << "data line before any keyword: " << line;
    Card& c = inp.cards.back();
    if (c.name == "HEADING") {
      c.data.push_back({line});
      continue;
    }
    const std::vector<std::string> entries = split(line);
    inp.max_entries = std::max(inp.max_entries, entries.size());
    for (const std::string& e : entries)
      if (e.find_first_of(".eE") != std::string::npos && !std::isalpha(static_cast<unsigned char>(e[0])))
        inp.longest_real = std::max(inp.longest_real, e.size());
    c.data.push_back(entries);
  }
  for (const Card& c : inp.cards) {
    if (c.name == "NODE") {
      for (const auto& d : c.data) {
        EXPECT_EQ(d.size(), 4u);
        EXPECT_TRUE(inp.nodes.emplace(integer(d[0]), Eigen::Vector3d(number(d[1]), number(d[2]), number(d[3]))).second)
            << "node defined twice: " << d[0];
      }
      if (!c.param("NSET").empty())
        for (const auto& [id, p] : inp.nodes) inp.nsets[upper(c.param("NSET"))].push_back(id);
    } else if (c.name == "ELEMENT") {
      const std::string set = upper(c.param("ELSET"));
      for (const auto& d : c.data) {
        const int id = integer(d[0]);
        std::vector<int> conn;
        for (std::size_t k = 1; k < d.size(); ++k) conn.push_back(integer(d[k]));
        EXPECT_TRUE(inp.elements.emplace(id, conn).second) << "element defined twice: " << id;
        inp.element_type[id] = upper(c.param("TYPE"));
        if (!set.empty()) inp.elsets[set].push_back(d[0]);
      }
    } else if (c.name == "ELSET") {
      auto& members = inp.elsets[upper(c.param("ELSET"))];
      for (const auto& d : c.data) members.insert(members.end(), d.begin(), d.end());
    } else if (c.name == "NSET") {
      auto& members = inp.nsets[upper(c.param("NSET"))];
      for (const auto& d : c.data)
        for (const std::string& e : d) members.push_back(integer(e));
    }
  }
  return inp;
}

struct Written {
  std::string text;
  std::vector<std::string> notes;
  Inp inp;
};

Written write(const Model& model, bool hybrid = false) {
  std::ostringstream out;
  AbaqusOptions options;
  options.hybrid = hybrid;
  Written w;
  w.notes = write_abaqus(model, out, options);
  w.text = out.str();
  w.inp = read_inp(w.text);
  return w;
}

bool has_note(const std::vector<std::string>& notes, const std::string& part) {
  return std::any_of(notes.begin(), notes.end(), [&](const std::string& n) { return n.find(part) != std::string::npos; });
}

void expect_round_trip(const Model& model, const Inp& inp) {
  // Nodes: ids 1..N, coordinates exactly the converted values (shortest round-trip printing).
  ASSERT_EQ(inp.nodes.size(), model.nodes.size());
  for (std::size_t i = 0; i < model.nodes.size(); ++i) {
    ASSERT_TRUE(inp.nodes.count(static_cast<int>(i) + 1));
    for (int k = 0; k < 3; ++k)
      EXPECT_EQ(inp.nodes.at(static_cast<int>(i) + 1)[k], length_from_mm(model.units, model.nodes[i][k])) << i;
  }
  // Elements: ids 1..E in model order, same connectivity, one type.
  const int npe = model.nodes_per_element();
  ASSERT_EQ(inp.elements.size(), model.elements.size());
  for (std::size_t e = 0; e < model.elements.size(); ++e) {
    const int id = static_cast<int>(e) + 1;
    ASSERT_TRUE(inp.elements.count(id));
    std::vector<int> expected;
    for (int k = 0; k < npe; ++k) expected.push_back(model.elements[e][k] + 1);
    EXPECT_EQ(inp.elements.at(id), expected) << "element " << id;
    EXPECT_EQ(inp.element_type.at(id), model.order == ElementOrder::Linear ? "C3D4" : "C3D10");
  }
  // Tissue sets, and EALL = all of them.
  std::set<int> all;
  for (std::size_t t = 0; t < model.tissue_names.size(); ++t) {
    std::set<int> expected;
    for (std::size_t e = 0; e < model.elements.size(); ++e)
      if (model.tissue_ids[e] == static_cast<int>(t) + 1) expected.insert(static_cast<int>(e) + 1);
    EXPECT_EQ(inp.element_ids(upper(model.tissue_names[t])), expected) << model.tissue_names[t];
    all.insert(expected.begin(), expected.end());
  }
  EXPECT_EQ(inp.element_ids("EALL"), all);
  // Node sets, 1-based.
  for (const NodeSet& s : model.node_sets) {
    std::vector<int> expected;
    for (int v : s.nodes) expected.push_back(v + 1);
    ASSERT_TRUE(inp.nsets.count(upper(s.name))) << s.name;
    EXPECT_EQ(inp.nsets.at(upper(s.name)), expected) << s.name;
  }
  // Face sets: *SURFACE lines "<SET>, Sk" over per-face element sets give back the (element, face) pairs.
  for (const FaceSet& s : model.face_sets) {
    std::set<std::pair<int, int>> expected, read;
    for (const auto& f : s.faces) expected.insert({f[0] + 1, f[1] + 1});
    for (const Card* c : inp.all("SURFACE")) {
      if (upper(c->param("NAME")) != upper(s.name)) continue;
      EXPECT_EQ(upper(c->param("TYPE")), "ELEMENT");
      for (const auto& d : c->data) {
        ASSERT_EQ(d.size(), 2u);
        ASSERT_EQ(d[1].size(), 2u);
        const int face = d[1][1] - '0';
        for (int id : inp.element_ids(upper(d[0]))) read.insert({id, face});
      }
    }
    EXPECT_EQ(read, expected) << s.name;
  }
  // CalculiX's line rules (docs/formats.md, "Abaqus / CalculiX"; ccx reads reals as f20.0 of the
  // first 20 chars).
  EXPECT_LE(inp.max_entries, 16u);
  EXPECT_LE(inp.longest_real, 20u);
}

TEST(Abaqus, RoundTripTet4) {
  const Model model = test::block_model();
  const Written w = write(model);
  expect_round_trip(model, w.inp);
  EXPECT_TRUE(has_note(w.notes, "C3D4 locks")) << "fat has K/mu = 333";
  // Deterministic.
  EXPECT_EQ(write(model).text, w.text);
}

TEST(Abaqus, RoundTripTet10) {
  test::BlockModelOptions options;
  options.order = ElementOrder::Quadratic;
  const Model model = test::block_model(options);
  const Written w = write(model);
  expect_round_trip(model, w.inp);
  EXPECT_FALSE(has_note(w.notes, "C3D4 locks"));
}

TEST(Abaqus, CoordinatesThatNeedTheFullFieldWidth) {
  // Awkward coordinates (SI metres, scaled by pi/7 * 1e-4): the shortest round-trip form of
  // many exceeds CalculiX's 20 characters and is printed with fewer digits; what is read back is
  // then within 1e-12 relative (13+ significant digits), and every field fits.
  Model model = test::block_model();
  model.units = UnitSystem::SI;
  for (Eigen::Vector3d& p : model.nodes) p = p * (M_PI / 7.0 * 1e-4) - Eigen::Vector3d(1e-3, 0.5, 3.0);
  const Written w = write(model);
  EXPECT_LE(w.inp.longest_real, 20u);
  for (std::size_t i = 0; i < model.nodes.size(); ++i)
    for (int k = 0; k < 3; ++k) {
      const double expected = length_from_mm(model.units, model.nodes[i][k]);
      EXPECT_LE(std::abs(w.inp.nodes.at(static_cast<int>(i) + 1)[k] - expected), 1e-12 * std::abs(expected)) << i;
    }
}

TEST(Abaqus, MaterialsInMegapascal) {
  const Model model = test::block_model();
  const Inp inp = write(model).inp;
  // Each *MATERIAL is followed by its *HYPERELASTIC and *DENSITY cards.
  auto material = [&](const std::string& name) {
    const std::size_t i = [&] {
      for (std::size_t k = 0; k < inp.cards.size(); ++k)
        if (inp.cards[k].name == "MATERIAL" && inp.cards[k].param("NAME") == name) return k;
      return inp.cards.size();
    }();
    EXPECT_LT(i + 2, inp.cards.size()) << name;
    EXPECT_EQ(inp.cards[i + 1].name, "HYPERELASTIC");
    EXPECT_EQ(inp.cards[i + 2].name, "DENSITY");
    return std::make_pair(inp.cards[i + 1], inp.cards[i + 2]);
  };
  auto near = [](double a, double b) { return std::abs(a - b) <= test::kRelativeRoundoff * std::abs(b); };
  {  // fat: neo-Hookean, mu 150 Pa, K 50 kPa, 950 kg/m^3
    const auto [hyper, density] = material("M_FAT");
    EXPECT_TRUE(hyper.params.count("NEO HOOKE"));
    ASSERT_EQ(hyper.data.size(), 1u);
    ASSERT_EQ(hyper.data[0].size(), 2u);
    EXPECT_TRUE(near(number(hyper.data[0][0]), 150.0 / 2 * 1e-6)) << "C10 = mu/2 in MPa";
    EXPECT_TRUE(near(number(hyper.data[0][1]), 2.0 / 0.05)) << "D1 = 2/K in 1/MPa";
    EXPECT_TRUE(near(number(density.data[0][0]), 950 * 1e-12)) << "t/mm^3";
  }
  {  // fgt: Mooney-Rivlin C10 100 Pa, C01 50 Pa, K 60 kPa
    const auto [hyper, density] = material("M_FGT");
    EXPECT_TRUE(hyper.params.count("MOONEY-RIVLIN"));
    ASSERT_EQ(hyper.data[0].size(), 3u);
    EXPECT_TRUE(near(number(hyper.data[0][0]), 1e-4));
    EXPECT_TRUE(near(number(hyper.data[0][1]), 5e-5));
    EXPECT_TRUE(near(number(hyper.data[0][2]), 2.0 / 0.06));
    EXPECT_TRUE(near(number(density.data[0][0]), 1.04e-9));
  }
  // One solid section per tissue with its material.
  std::set<std::string> sections;
  for (const Card* c : inp.all("SOLID SECTION")) {
    EXPECT_EQ(c->param("MATERIAL"), "M_" + c->param("ELSET"));
    sections.insert(c->param("ELSET"));
  }
  EXPECT_EQ(sections, (std::set<std::string>{"FAT", "FGT", "TUMOR"}));
  EXPECT_TRUE(inp.cards[0].name == "HEADING");
  EXPECT_NE(inp.cards[0].data[0][0].find("mm-t-s"), std::string::npos) << "units in the heading";
}

TEST(Abaqus, OgdenTermsAndDataLines) {
  test::BlockModelOptions options;
  options.ogden_tumor = true;
  Model model = test::block_model(options);
  auto tumor = [&](const Inp& inp) {
    for (std::size_t k = 0; k + 1 < inp.cards.size(); ++k)
      if (inp.cards[k].name == "MATERIAL" && inp.cards[k].param("NAME") == "M_TUMOR") return inp.cards[k + 1];
    ADD_FAILURE() << "no M_TUMOR";
    return Card{};
  };
  // N=2 (mu 700/200 Pa, alpha 2/-2): mu1, alpha1, mu2, alpha2, D1, D2 on one line. D2 is not 0:
  // CalculiX would replace a zero D2 by (0.1/mu)^2 (ccx 2.20, run); D1 * 1e12 makes it vanish.
  const Card two = tumor(write(model).inp);
  EXPECT_EQ(two.param("N"), "2");
  EXPECT_TRUE(two.params.count("OGDEN"));
  ASSERT_EQ(two.data.size(), 1u);
  const std::vector<double> expected2{7e-4, 2.0, 2e-4, -2.0, 2.0 / 0.1, 2.0 / 0.1 * 1e12};
  ASSERT_EQ(two.data[0].size(), expected2.size());
  for (std::size_t i = 0; i < expected2.size(); ++i)
    EXPECT_NEAR(number(two.data[0][i]), expected2[i], test::kRelativeRoundoff * std::abs(expected2[i])) << i;
  // N=3: 8 values on the first line (mu1..alpha3, D1, D2), D3 on the second (CalculiX CrunchiX
  // User's Manual 2.20, *HYPERELASTIC).
  model.materials[2].ogden.push_back({100.0, 5.0});
  model.materials[2].mu_Pa += 100.0;  // mu = sum of mu_i
  const Card three = tumor(write(model).inp);
  EXPECT_EQ(three.param("N"), "3");
  ASSERT_EQ(three.data.size(), 2u);
  EXPECT_EQ(three.data[0].size(), 8u);
  ASSERT_EQ(three.data[1].size(), 1u);
  EXPECT_NEAR(number(three.data[0][4]), 1e-4, 1e-4 * test::kRelativeRoundoff);
  EXPECT_NEAR(number(three.data[0][6]), 20.0, 20.0 * test::kRelativeRoundoff);
  for (const std::string& D : {three.data[0][7], three.data[1][0]})  // D2, D3 = D1 * 1e12
    EXPECT_NEAR(number(D), 20.0 * 1e12, 20.0 * 1e12 * test::kRelativeRoundoff);
}

TEST(Abaqus, StepGravityAndOutput) {
  const Model model = test::block_model();
  const Inp inp = write(model).inp;
  const std::size_t step = inp.index("STEP");
  ASSERT_LT(step, inp.cards.size());
  EXPECT_LT(inp.index("BOUNDARY"), step) << "homogeneous BCs in the model data";
  const Card& boundary = inp.cards[inp.index("BOUNDARY")];
  ASSERT_EQ(boundary.data.size(), 1u);
  EXPECT_EQ(boundary.data[0], (std::vector<std::string>{"CHEST_WALL", "1", "3"}));
  EXPECT_TRUE(inp.cards[step].params.count("NLGEOM"));
  EXPECT_EQ(inp.cards[step].param("INC"), "100");
  const Card& stat = inp.cards[inp.index("STATIC")];
  ASSERT_EQ(stat.data.at(0).size(), 4u);
  EXPECT_EQ(number(stat.data[0][0]), 0.1);
  EXPECT_EQ(number(stat.data[0][1]), 1.0);
  EXPECT_EQ(number(stat.data[0][2]), 1e-4);
  EXPECT_EQ(number(stat.data[0][3]), 0.1);
  // Prone gravity 9.81 m/s^2 = 9810 mm/s^2 towards anterior (-y).
  const Card& dload = inp.cards[inp.index("DLOAD")];
  ASSERT_EQ(dload.data.size(), 1u);
  ASSERT_EQ(dload.data[0].size(), 6u);
  EXPECT_EQ(dload.data[0][0], "EALL");
  EXPECT_EQ(dload.data[0][1], "GRAV");
  EXPECT_NEAR(number(dload.data[0][2]), 9810.0, 9810.0 * test::kRelativeRoundoff);
  EXPECT_EQ(Eigen::Vector3d(number(dload.data[0][3]), number(dload.data[0][4]), number(dload.data[0][5])),
            Eigen::Vector3d(0, -1, 0));
  // Output: U of all nodes, RF totals of the fixed set.
  bool u = false, rf = false;
  for (const Card* c : inp.all("NODE PRINT")) {
    u = u || (c->param("NSET") == "NALL" && c->data.at(0).at(0) == "U");
    rf = rf || (c->param("NSET") == "CHEST_WALL" && c->param("TOTALS") == "YES" && c->data.at(0).at(0) == "RF");
  }
  EXPECT_TRUE(u);
  EXPECT_TRUE(rf);
  EXPECT_EQ(inp.cards.back().name, "END STEP");
  // No gravity: no *DLOAD, and a note.
  Model still = model;
  still.gravity.acceleration_m_s2.setZero();
  const Written w = write(still);
  EXPECT_EQ(w.inp.index("DLOAD"), w.inp.cards.size());
  EXPECT_TRUE(has_note(w.notes, "gravity is zero"));
}

TEST(Abaqus, HybridElementsAreAbaqusOnly) {
  const Written w = write(test::block_model(), true);
  for (const auto& [id, type] : w.inp.element_type) ASSERT_EQ(type, "C3D4H") << id;
  EXPECT_TRUE(has_note(w.notes, "CalculiX rejects"));
}

TEST(Abaqus, RefusesCompressibleNeoHookean) {
  Model model = test::block_model();
  model.materials[0].law = MaterialLaw::CompressibleNeoHookean;
  std::ostringstream out;
  try {
    write_abaqus(model, out, {});
    FAIL() << "no error";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("'fat'"), std::string::npos) << what;
    EXPECT_NE(what.find("use neo-hookean"), std::string::npos) << what;
  }
  EXPECT_TRUE(out.str().empty()) << "refused before writing anything";
}

TEST(Abaqus, RefusesNamesThatClashOnceUpperCased) {
  Model model = test::block_model();
  model.tissue_names[1] = "Fat";  // FAT twice
  std::ostringstream out;
  EXPECT_THROW(write_abaqus(model, out, {}), InputError);
  model = test::block_model();
  model.tissue_names[1] = "eall";
  EXPECT_THROW(write_abaqus(model, out, {}), InputError);
}

/// Equations "n . u = 0" of the deck: node -> list of (dof, coefficient), dependent term first.
std::map<int, std::vector<std::pair<int, double>>> equations(const Inp& inp) {
  std::map<int, std::vector<std::pair<int, double>>> eqs;
  for (const Card* c : inp.all("EQUATION"))
    for (std::size_t i = 0; i < c->data.size(); i += 2) {
      const int terms = integer(c->data[i].at(0));
      const auto& d = c->data.at(i + 1);
      EXPECT_EQ(d.size(), 3u * terms);
      const int node = integer(d[0]);
      EXPECT_FALSE(eqs.count(node)) << "two equations for node " << node;
      for (int t = 0; t < terms; ++t) {
        EXPECT_EQ(integer(d[3 * t]), node) << "one node per equation";
        eqs[node].push_back({integer(d[3 * t + 1]), number(d[3 * t + 2])});
      }
    }
  return eqs;
}

TEST(Abaqus, SlidingSetAsEquations) {
  test::BlockModelOptions options;
  options.sliding_top = true;
  Model model = test::block_model(options);
  const NodeSet& top = model.node_sets.at(1);
  const NodeSet& wall = model.node_sets.at(0);
  ASSERT_EQ(top.constraint, Constraint::Sliding);
  // build_model leaves nodes of fixed sets out of sliding sets; put the shared edge
  // (y = 10, z = 10) back in to see the writer keep those nodes fixed without an equation.
  std::set<int> free_top;
  for (int v : top.nodes) free_top.insert(v + 1);
  std::map<int, Eigen::Vector3d> with_edge;
  for (std::size_t i = 0; i < top.nodes.size(); ++i) with_edge[top.nodes[i]] = top.normals[i];
  for (int v : wall.nodes)
    if (model.nodes[v].z() == 10.0) with_edge[v] = Eigen::Vector3d::UnitZ();
  ASSERT_GT(with_edge.size(), top.nodes.size());
  model.node_sets[1].nodes.clear();
  model.node_sets[1].normals.clear();
  for (const auto& [v, n] : with_edge) {
    model.node_sets[1].nodes.push_back(v);
    model.node_sets[1].normals.push_back(n);
  }
  Written w = write(model);
  expect_round_trip(model, w.inp);
  EXPECT_LT(w.inp.index("EQUATION"), w.inp.index("STEP"));
  auto eqs = equations(w.inp);
  ASSERT_EQ(eqs.size(), free_top.size());
  for (const auto& [node, terms] : eqs) {
    EXPECT_TRUE(free_top.count(node)) << node;
    // Normal +z: one term, u_z = 0.
    ASSERT_EQ(terms.size(), 1u);
    EXPECT_EQ(terms[0].first, 3);
    EXPECT_EQ(terms[0].second, 1.0);
  }
  EXPECT_TRUE(has_note(w.notes, "also in a fixed set"));

  // A tilted normal (0, 0.6, 0.8): the dependent term is z (largest), then y; x (0) is left out.
  for (Eigen::Vector3d& n : model.node_sets[1].normals) n = Eigen::Vector3d(0.0, 0.6, 0.8);
  w = write(model);
  eqs = equations(w.inp);
  ASSERT_EQ(eqs.size(), free_top.size());
  for (const auto& [node, terms] : eqs) {
    ASSERT_EQ(terms.size(), 2u) << node;
    EXPECT_EQ(terms[0], std::make_pair(3, 0.8));
    EXPECT_EQ(terms[1], std::make_pair(2, 0.6));
  }
  EXPECT_LE(w.inp.max_entries, 16u);
}

}  // namespace
}  // namespace tissuemesh
