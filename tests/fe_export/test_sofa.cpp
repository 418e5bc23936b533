// SOFA is not installed: the scene is checked rule by rule (docs/formats.md, "SOFA") after parsing
// it with VTK's XML parser, and its companion legacy VTK mesh is read back with VTK's legacy
// reader.
#include "core/errors.h"
#include "fe_export/sofa/write_sofa.h"
#include "support/model_fixture.h"
#include "support/test_paths.h"

#include <gtest/gtest.h>
#include <vtkCellData.h>
#include <vtkCellType.h>
#include <vtkDataArray.h>
#include <vtkNew.h>
#include <vtkSmartPointer.h>
#include <vtkUnstructuredGrid.h>
#include <vtkUnstructuredGridReader.h>
#include <vtkXMLDataElement.h>
#include <vtkXMLUtilities.h>

#include <algorithm>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

namespace tissuemesh {
namespace {

using test::BlockModelOptions;
using test::block_model;

// Plugin of each component (SOFA documentation, "Components"; PlaneProjectiveConstraint: registered
// in Sofa/Component/Constraint/Projective/.../PlaneProjectiveConstraint.cpp). DefaultAnimationLoop
// lives in Sofa.Simulation.Core and needs no plugin. Grouped by plugin (the writer keeps the
// inverse table): the test's own record of that list.
const std::map<std::string, std::set<std::string>> kComponentsOf{
    {"Sofa.Component.ODESolver.Backward", {"NewtonRaphsonSolver", "StaticSolver"}},
    {"Sofa.Component.LinearSolver.Direct", {"SparseLDLSolver"}},
    {"Sofa.Component.IO.Mesh", {"MeshVTKLoader"}},
    {"Sofa.Component.Topology.Container.Dynamic",
     {"TetrahedronSetTopologyContainer", "TetrahedronSetGeometryAlgorithms"}},
    {"Sofa.Component.StateContainer", {"MechanicalObject"}},
    {"Sofa.Component.Mass", {"MeshMatrixMass"}},
    {"Sofa.Component.Constraint.Projective", {"FixedProjectiveConstraint", "PlaneProjectiveConstraint"}},
    {"Sofa.Component.SolidMechanics.FEM.HyperElastic", {"TetrahedronHyperelasticityFEMForceField"}},
};

std::string plugin_of(const std::string& component) {
  for (const auto& [plugin, components] : kComponentsOf)
    if (components.count(component)) return plugin;
  return "";
}

struct Scene {
  vtkSmartPointer<vtkXMLDataElement> root;
  std::vector<std::string> notes;
  std::string text;
};

Scene write_scene(const Model& model, const std::string& version = "25.06") {
  SofaOptions options;
  options.version = version;
  options.mesh_file = "block.vtk";
  std::ostringstream out;
  Scene s;
  s.notes = write_sofa(model, out, options);
  s.text = out.str();
  std::istringstream in(s.text);
  s.root = vtkSmartPointer<vtkXMLDataElement>::Take(vtkXMLUtilities::ReadElementFromStream(in));
  return s;
}

void collect(vtkXMLDataElement* e, const std::string& name, std::vector<vtkXMLDataElement*>& out) {
  if (name.empty() || name == e->GetName()) out.push_back(e);
  for (int i = 0; i < e->GetNumberOfNestedElements(); ++i) collect(e->GetNestedElement(i), name, out);
}

std::vector<vtkXMLDataElement*> all(vtkXMLDataElement* e, const std::string& name) {
  std::vector<vtkXMLDataElement*> out;
  collect(e, name, out);
  return out;
}

vtkXMLDataElement* child(vtkXMLDataElement* e, const std::string& name) {
  for (int i = 0; i < e->GetNumberOfNestedElements(); ++i)
    if (name == e->GetNestedElement(i)->GetName()) return e->GetNestedElement(i);
  return nullptr;
}

vtkXMLDataElement* node_named(vtkXMLDataElement* e, const std::string& name) {
  for (vtkXMLDataElement* n : all(e, "Node"))
    if (n->GetAttribute("name") != nullptr && name == n->GetAttribute("name")) return n;
  return nullptr;
}

std::string attr(vtkXMLDataElement* e, const char* name) {
  const char* v = e->GetAttribute(name);
  return v == nullptr ? "<missing>" : v;
}

std::vector<double> numbers(vtkXMLDataElement* e, const char* name) {
  std::istringstream in(attr(e, name));
  std::vector<double> out;
  for (double v; in >> v;) out.push_back(v);
  return out;
}

std::vector<int> integers(vtkXMLDataElement* e, const char* name) {
  std::istringstream in(attr(e, name));
  std::vector<int> out;
  for (int v; in >> v;) out.push_back(v);
  return out;
}

const NodeSet& set_named(const Model& m, const std::string& name) {
  for (const NodeSet& s : m.node_sets)
    if (s.name == name) return s;
  throw std::runtime_error("no set " + name);
}

TEST(SofaScene, RequiresExactlyThePluginsOfTheComponentsUsed) {
  BlockModelOptions o;
  o.sliding_top = true;
  for (const std::string version : {"25.06", "24.06"}) {
    const Scene s = write_scene(block_model(o), version);
    ASSERT_NE(s.root, nullptr) << s.text;
    std::set<std::string> required, needed;
    for (vtkXMLDataElement* e : all(s.root, "RequiredPlugin")) {
      EXPECT_EQ(e->GetAttribute("name"), nullptr) << "deprecated RequiredPlugin name=";
      required.insert(attr(e, "pluginName"));
    }
    for (vtkXMLDataElement* e : all(s.root, "")) {
      const std::string n = e->GetName();
      if (n == "Node" || n == "RequiredPlugin" || n == "DefaultAnimationLoop") continue;
      ASSERT_FALSE(plugin_of(n).empty()) << "component without known plugin: " << n;
      needed.insert(plugin_of(n));
    }
    EXPECT_EQ(required, needed) << version;
    EXPECT_EQ(all(s.root, "DefaultAnimationLoop").size(), 1u);
  }
  // No constraint, no constraint plugin.
  Model m = block_model();
  m.node_sets.clear();
  const Scene s = write_scene(m);
  for (vtkXMLDataElement* e : all(s.root, "RequiredPlugin"))
    EXPECT_NE(attr(e, "pluginName"), "Sofa.Component.Constraint.Projective");
}

TEST(SofaScene, GravityIsThePhysicalAccelerationInModelUnits) {
  const Scene mm = write_scene(block_model());  // prone: -y, mm-t-s
  EXPECT_EQ(std::string(mm.root->GetName()), "Node");
  EXPECT_EQ(attr(mm.root, "dt"), "1");
  EXPECT_EQ(numbers(mm.root, "gravity"), (std::vector<double>{0, -9810, 0}));
  BlockModelOptions si;
  si.units = UnitSystem::SI;
  EXPECT_EQ(numbers(write_scene(block_model(si)).root, "gravity"), (std::vector<double>{0, -9.81, 0}));
}

TEST(SofaScene, MainNodeComponentsAndLinks) {
  const Scene s = write_scene(block_model());
  vtkXMLDataElement* body = node_named(s.root, "breast");
  ASSERT_NE(body, nullptr);
  EXPECT_EQ(attr(child(body, "SparseLDLSolver"), "template"), "CompressedRowSparseMatrixMat3x3d");
  EXPECT_EQ(attr(child(body, "MeshVTKLoader"), "filename"), "block.vtk");
  EXPECT_EQ(attr(child(body, "MeshVTKLoader"), "name"), "loader");
  vtkXMLDataElement* topo = child(body, "TetrahedronSetTopologyContainer");
  EXPECT_EQ(attr(topo, "name"), "topology");
  EXPECT_EQ(attr(topo, "src"), "@loader");
  EXPECT_EQ(attr(child(body, "TetrahedronSetGeometryAlgorithms"), "template"), "Vec3d");
  EXPECT_EQ(attr(child(body, "MechanicalObject"), "name"), "dofs");
  EXPECT_EQ(attr(child(body, "MechanicalObject"), "template"), "Vec3d");
  EXPECT_EQ(attr(child(body, "MeshMatrixMass"), "topology"), "@topology");
}

TEST(SofaScene, FixedIndicesAreTheZeroBasedSetNodes) {
  const Model m = block_model();
  const Scene s = write_scene(m);
  const auto fixed = all(s.root, "FixedProjectiveConstraint");
  ASSERT_EQ(fixed.size(), 1u);
  EXPECT_EQ(attr(fixed[0], "name"), "fixed_chest_wall");
  const std::vector<int> idx = integers(fixed[0], "indices");
  EXPECT_EQ(idx, set_named(m, "chest_wall").nodes);
  EXPECT_EQ(idx.size(), 66u);  // 11 x 6 grid nodes on the plane y = 10
  for (int i : idx) {
    EXPECT_GE(i, 0);
    EXPECT_LT(i, m.num_corner_nodes);
    EXPECT_EQ(m.nodes[i].y(), 10.0);
  }
}

TEST(SofaScene, OneChildNodePerTissueWithItsTets) {
  const Model m = block_model();
  const Scene s = write_scene(m);
  std::size_t total = 0;
  for (std::size_t t = 0; t < m.tissue_names.size(); ++t) {
    vtkXMLDataElement* node = node_named(s.root, m.tissue_names[t]);
    ASSERT_NE(node, nullptr) << m.tissue_names[t];
    vtkXMLDataElement* topo = child(node, "TetrahedronSetTopologyContainer");
    ASSERT_NE(topo, nullptr);
    EXPECT_EQ(attr(topo, "name"), "t");
    std::vector<int> expected;
    for (std::size_t e = 0; e < m.elements.size(); ++e)
      if (m.tissue_ids[e] == static_cast<int>(t + 1)) expected.insert(expected.end(), m.elements[e].begin(), m.elements[e].begin() + 4);
    EXPECT_EQ(integers(topo, "tetrahedra"), expected) << m.tissue_names[t];
    total += expected.size() / 4;
    vtkXMLDataElement* ff = child(node, "TetrahedronHyperelasticityFEMForceField");
    ASSERT_NE(ff, nullptr);
    EXPECT_EQ(attr(ff, "topology"), "@t");
    EXPECT_EQ(child(node, "MechanicalObject"), nullptr) << "children act on the parent's DOFs";
  }
  EXPECT_EQ(total, m.elements.size());
  EXPECT_EQ(all(s.root, "TetrahedronHyperelasticityFEMForceField").size(), m.tissue_names.size());
}

TEST(SofaScene, ParameterSetsInSofaOrderAndModelUnits) {
  // EXPECT_DOUBLE_EQ (4 ulps): the writer converts with stress_from_pascal (Pa * 1e-6), which may
  // differ from the correctly rounded literal in the last bit; a wrong order or unit is off by far more.
  Model m = block_model();  // fat neo-Hookean, fgt and tumor Mooney-Rivlin, MPa
  const Scene s = write_scene(m);
  auto ff = [&](const Scene& sc, const std::string& tissue) {
    return child(node_named(sc.root, tissue), "TetrahedronHyperelasticityFEMForceField");
  };
  // Uncoupled neo-Hookean -> MooneyRivlin "C10 0 K".
  EXPECT_EQ(attr(ff(s, "fat"), "materialName"), "MooneyRivlin");
  const auto fat = numbers(ff(s, "fat"), "ParameterSet");
  ASSERT_EQ(fat.size(), 3u);
  EXPECT_DOUBLE_EQ(fat[0], 75e-6);
  EXPECT_EQ(fat[1], 0.0);
  EXPECT_DOUBLE_EQ(fat[2], 50e3 * 1e-6);
  // Mooney-Rivlin -> "C10 C01 K".
  EXPECT_EQ(attr(ff(s, "fgt"), "materialName"), "MooneyRivlin");
  const auto fgt = numbers(ff(s, "fgt"), "ParameterSet");
  ASSERT_EQ(fgt.size(), 3u);
  EXPECT_DOUBLE_EQ(fgt[0], 100e-6);
  EXPECT_DOUBLE_EQ(fgt[1], 50e-6);
  EXPECT_DOUBLE_EQ(fgt[2], 60e3 * 1e-6);
  // The (J-1)^2 vs (ln J)^2 note names the approximated tissues.
  ASSERT_EQ(s.notes.size(), 1u);
  EXPECT_NE(s.notes[0].find("ln J"), std::string::npos);
  EXPECT_NE(s.notes[0].find("fat"), std::string::npos);
  EXPECT_NE(s.notes[0].find("tumor"), std::string::npos);

  // Compressible neo-Hookean -> NeoHookean "mu lambda", lambda = K - 2 mu / 3 (Lame, not K); no note.
  for (MaterialSpec& spec : m.materials) {
    spec.law = MaterialLaw::CompressibleNeoHookean;
    spec.mu_Pa = 300;
  }
  const Scene c = write_scene(m);
  EXPECT_TRUE(c.notes.empty());
  for (std::size_t t = 0; t < m.tissue_names.size(); ++t) {
    EXPECT_EQ(attr(ff(c, m.tissue_names[t]), "materialName"), "NeoHookean");
    const auto p = numbers(ff(c, m.tissue_names[t]), "ParameterSet");
    ASSERT_EQ(p.size(), 2u);
    EXPECT_DOUBLE_EQ(p[0], 300e-6);
    EXPECT_DOUBLE_EQ(p[1], (m.materials[t].K_Pa - 2.0 * 300 / 3.0) * 1e-6);
  }
}

TEST(SofaScene, MassDensityOnePerTetInModelUnits) {
  const Model m = block_model();
  const Scene s = write_scene(m);
  const auto rho = numbers(child(node_named(s.root, "breast"), "MeshMatrixMass"), "massDensity");
  ASSERT_EQ(rho.size(), m.elements.size());
  const double expected[] = {950e-12, 1040e-12, 1060e-12};  // t/mm^3
  for (std::size_t e = 0; e < rho.size(); ++e) EXPECT_DOUBLE_EQ(rho[e], expected[m.tissue_ids[e] - 1]) << e;
}

TEST(SofaScene, SolverLayoutFollowsTheVersion) {
  Model m = block_model();
  m.analysis.max_newton_iterations = 37;
  const Scene v25 = write_scene(m, "25.06");
  vtkXMLDataElement* body = node_named(v25.root, "breast");
  vtkXMLDataElement* nr = child(body, "NewtonRaphsonSolver");
  ASSERT_NE(nr, nullptr);
  EXPECT_EQ(attr(nr, "name"), "newton");
  EXPECT_EQ(attr(nr, "maxNbIterationsNewton"), "37");
  EXPECT_NE(nr->GetAttribute("maxNbIterationsLineSearch"), nullptr);
  EXPECT_EQ(numbers(nr, "relativeInitialStoppingThreshold"), std::vector<double>{m.analysis.residual_tolerance});
  vtkXMLDataElement* st = child(body, "StaticSolver");
  ASSERT_NE(st, nullptr);
  EXPECT_EQ(attr(st, "newtonSolver"), "@newton");
  EXPECT_EQ(st->GetAttribute("newton_iterations"), nullptr) << "removed in v25.12";

  const Scene v24 = write_scene(m, "24.06");
  body = node_named(v24.root, "breast");
  EXPECT_EQ(child(body, "NewtonRaphsonSolver"), nullptr);
  st = child(body, "StaticSolver");
  ASSERT_NE(st, nullptr);
  EXPECT_EQ(attr(st, "newton_iterations"), "37");
  EXPECT_EQ(numbers(st, "relative_correction_tolerance_threshold"),
            std::vector<double>{m.analysis.displacement_tolerance});
  EXPECT_EQ(numbers(st, "relative_residual_tolerance_threshold"), std::vector<double>{m.analysis.residual_tolerance});
  EXPECT_NE(st->GetAttribute("absolute_residual_tolerance_threshold"), nullptr);
  EXPECT_NE(st->GetAttribute("absolute_correction_tolerance_threshold"), nullptr);
  EXPECT_EQ(st->GetAttribute("newtonSolver"), nullptr);

  std::ostringstream out;
  SofaOptions bad;
  bad.version = "23.12";
  try {
    write_sofa(m, out, bad);
    FAIL() << "version 23.12 accepted";
  } catch (const InputError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("23.12"), std::string::npos) << msg;
    EXPECT_NE(msg.find("24.06"), std::string::npos) << msg;
    EXPECT_NE(msg.find("25.06"), std::string::npos) << msg;
  }
  EXPECT_TRUE(out.str().empty());
}

TEST(SofaScene, RefusesOgdenNamingTheTissue) {
  BlockModelOptions o;
  o.ogden_tumor = true;
  std::ostringstream out;
  try {
    write_sofa(block_model(o), out, SofaOptions{});
    FAIL() << "Ogden accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("'tumor'"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("Ogden"), std::string::npos) << e.what();
  }
  EXPECT_TRUE(out.str().empty()) << "nothing written for a refused model";
}

TEST(SofaScene, PlanarSlidingSetBecomesAPlaneProjectiveConstraint) {
  BlockModelOptions o;
  o.sliding_top = true;
  const Model m = block_model(o);
  const Scene s = write_scene(m);
  const auto planes = all(s.root, "PlaneProjectiveConstraint");
  ASSERT_EQ(planes.size(), 1u);
  EXPECT_EQ(attr(planes[0], "name"), "sliding_top");
  EXPECT_EQ(integers(planes[0], "indices"), set_named(m, "top").nodes);
  EXPECT_EQ(numbers(planes[0], "normal"), (std::vector<double>{0, 0, 1}));
  const auto origin = numbers(planes[0], "origin");
  ASSERT_EQ(origin.size(), 3u);
  EXPECT_EQ(origin[2], 10.0);
}

TEST(SofaScene, RefusesCurvedOrNonPlanarSlidingSets) {
  BlockModelOptions o;
  o.sliding_top = true;
  const Model planar = block_model(o);
  auto refusal = [](const Model& m) {
    std::ostringstream out;
    try {
      write_sofa(m, out, SofaOptions{});
    } catch (const InputError& e) {
      EXPECT_TRUE(out.str().empty());
      return std::string(e.what());
    }
    return std::string("no error");
  };
  Model curved = planar;
  for (NodeSet& s : curved.node_sets)
    if (s.name == "top") s.normals[3] = Eigen::Vector3d(0, std::sin(0.01), std::cos(0.01));
  const std::string msg = refusal(curved);
  EXPECT_NE(msg.find("'top'"), std::string::npos) << msg;
  EXPECT_NE(msg.find("not all parallel"), std::string::npos) << msg;

  Model two_planes = planar;  // parallel normals, but one node on the plane z = 8
  const int at_z8 = static_cast<int>(std::find(planar.nodes.begin(), planar.nodes.end(), Eigen::Vector3d(0, 0, 8)) -
                                     planar.nodes.begin());  // the node (0, 0, 8), wherever it was numbered
  ASSERT_LT(at_z8, planar.num_corner_nodes);
  for (NodeSet& s : two_planes.node_sets)
    if (s.name == "top") {  // inserted in place: node sets stay sorted
      const auto pos = std::lower_bound(s.nodes.begin(), s.nodes.end(), at_z8);
      s.normals.insert(s.normals.begin() + (pos - s.nodes.begin()), Eigen::Vector3d(0, 0, 1));
      s.nodes.insert(pos, at_z8);
    }
  const std::string msg2 = refusal(two_planes);
  EXPECT_NE(msg2.find("'top'"), std::string::npos) << msg2;
  EXPECT_NE(msg2.find("not planar"), std::string::npos) << msg2;
}

TEST(SofaScene, Tet10IsWrittenAsItsCornersWithANote) {
  BlockModelOptions o;
  o.order = ElementOrder::Quadratic;
  o.sliding_top = true;
  const Model m = block_model(o);
  ASSERT_GT(m.nodes.size(), static_cast<std::size_t>(m.num_corner_nodes));
  const Scene s = write_scene(m);
  EXPECT_TRUE(std::any_of(s.notes.begin(), s.notes.end(),
                          [](const std::string& n) { return n.find("tet10") != std::string::npos; }));
  for (const char* name : {"FixedProjectiveConstraint", "PlaneProjectiveConstraint"}) {
    const auto c = all(s.root, name);
    ASSERT_EQ(c.size(), 1u);
    std::vector<int> corners;
    const std::string constraint = attr(c[0], "name");  // fixed_<set> / sliding_<set>
    for (int n : set_named(m, constraint.substr(constraint.find('_') + 1)).nodes)
      if (n < m.num_corner_nodes) corners.push_back(n);
    EXPECT_EQ(integers(c[0], "indices"), corners) << name;
  }
  for (vtkXMLDataElement* t : all(s.root, "TetrahedronSetTopologyContainer"))
    for (int v : integers(t, "tetrahedra")) EXPECT_LT(v, m.num_corner_nodes);
}

TEST(SofaScene, IsDeterministic) {
  const Model m = block_model();
  EXPECT_EQ(write_scene(m).text, write_scene(m).text);
}

vtkSmartPointer<vtkUnstructuredGrid> read_legacy(const std::string& path, vtkUnstructuredGridReader* reader) {
  reader->SetFileName(path.c_str());
  reader->Update();
  return reader->GetOutput();
}

void check_legacy_vtk(const Model& m, double length_scale) {
  const auto path = (test::scratch_dir() / "block.vtk").string();
  {
    std::ofstream out(path);
    write_legacy_vtk(m, out);
  }
  std::ifstream in(path);
  std::string header;
  std::getline(in, header);
  EXPECT_EQ(header, "# vtk DataFile Version 4.2");
  vtkNew<vtkUnstructuredGridReader> reader;
  vtkSmartPointer<vtkUnstructuredGrid> grid = read_legacy(path, reader);
  EXPECT_EQ(reader->GetFileMajorVersion(), 4);
  EXPECT_EQ(reader->GetFileMinorVersion(), 2);
  EXPECT_EQ(reader->GetFileType(), VTK_ASCII);
  ASSERT_EQ(grid->GetNumberOfPoints(), m.num_corner_nodes);
  for (vtkIdType i = 0; i < grid->GetNumberOfPoints(); ++i) {
    double p[3];
    grid->GetPoint(i, p);
    for (int k = 0; k < 3; ++k) ASSERT_EQ(p[k], m.nodes[i][k] * length_scale) << i;
  }
  ASSERT_EQ(grid->GetNumberOfCells(), static_cast<vtkIdType>(m.elements.size()));
  vtkDataArray* ids = grid->GetCellData()->GetArray("tissue_id");
  ASSERT_NE(ids, nullptr);
  for (vtkIdType c = 0; c < grid->GetNumberOfCells(); ++c) {
    ASSERT_EQ(grid->GetCellType(c), VTK_TETRA);
    const vtkIdType* pts = nullptr;
    vtkIdType n = 0;
    grid->GetCellPoints(c, n, pts);
    ASSERT_EQ(n, 4);
    for (int k = 0; k < 4; ++k) ASSERT_EQ(pts[k], m.elements[c][k]) << c;
    ASSERT_EQ(ids->GetTuple1(c), m.tissue_ids[c]);
  }
}

TEST(SofaLegacyVtk, ReadsBackIdenticalPointsAndTets) {
  check_legacy_vtk(block_model(), 1.0);
  BlockModelOptions si;
  si.units = UnitSystem::SI;  // metres: the scene and its mesh share the model's length unit
  check_legacy_vtk(block_model(si), 1e-3);
  BlockModelOptions q;
  q.order = ElementOrder::Quadratic;
  check_legacy_vtk(block_model(q), 1.0);  // corner nodes and linear tets only
}

}  // namespace
}  // namespace tissuemesh
