// SOFA scene writer (docs/formats.md, "SOFA"). Everything that can refuse the model (version,
// Ogden, curved sliding sets) is checked before the first character is written.
//
// Why the component names: the older names ProjectToPlaneConstraint and FixedConstraint are
// deprecated in SOFA v24.06 and removed in v25.06 (SOFA sources: ComponentChange.cpp,
// PlaneProjectiveConstraint.cpp), so the scene uses PlaneProjectiveConstraint and
// FixedProjectiveConstraint, which both versions know. PlaneProjectiveConstraint also projects
// positions onto its plane, hence only coplanar sliding sets are written.
#include "fe_export/sofa/write_sofa.h"

#include "core/errors.h"
#include "fe_export/text_format.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <sstream>

namespace tissuemesh {

namespace {

std::string vec3(const Eigen::Vector3d& v) {
  return shortest_decimal(v.x()) + " " + shortest_decimal(v.y()) + " " + shortest_decimal(v.z());
}

// Plugin of every component the scene may use (SOFA documentation, "Components";
// PlaneProjectiveConstraint is registered in Sofa.Component.Constraint.Projective,
// PlaneProjectiveConstraint.cpp).
const char* plugin_of(const std::string& component) {
  static const std::array<std::pair<const char*, const char*>, 11> kPlugins{{
      {"NewtonRaphsonSolver", "Sofa.Component.ODESolver.Backward"},
      {"StaticSolver", "Sofa.Component.ODESolver.Backward"},
      {"SparseLDLSolver", "Sofa.Component.LinearSolver.Direct"},
      {"MeshVTKLoader", "Sofa.Component.IO.Mesh"},
      {"TetrahedronSetTopologyContainer", "Sofa.Component.Topology.Container.Dynamic"},
      {"TetrahedronSetGeometryAlgorithms", "Sofa.Component.Topology.Container.Dynamic"},
      {"MechanicalObject", "Sofa.Component.StateContainer"},
      {"MeshMatrixMass", "Sofa.Component.Mass"},
      {"FixedProjectiveConstraint", "Sofa.Component.Constraint.Projective"},
      {"PlaneProjectiveConstraint", "Sofa.Component.Constraint.Projective"},
      {"TetrahedronHyperelasticityFEMForceField", "Sofa.Component.SolidMechanics.FEM.HyperElastic"},
  }};
  for (const auto& [c, p] : kPlugins)
    if (component == c) return p;
  throw std::logic_error("write_sofa: no plugin known for component " + component);
}

struct SlidingPlane {
  const NodeSet* set = nullptr;
  std::vector<int> corners;
  Eigen::Vector3d origin_mm;
  Eigen::Vector3d normal;
};

// Corner nodes (0-based) of a set: SOFA's mesh holds the corners only.
std::vector<int> corner_nodes(const Model& model, const NodeSet& set) {
  std::vector<int> out;
  for (int n : set.nodes)
    if (n < model.num_corner_nodes) out.push_back(n);
  return out;
}

// A sliding set is representable by one PlaneProjectiveConstraint when all its normals are
// parallel (|n_i x n_0| <= 1e-6; an opposite normal gives the same constraint n.u = 0) and its
// corner nodes lie on one plane (the constraint also projects positions onto the plane through
// `origin`, so a second parallel plane would be snapped onto the first).
SlidingPlane sliding_plane(const Model& model, const NodeSet& set) {
  constexpr double kParallel = 1e-6;
  SlidingPlane p;
  p.set = &set;
  p.corners = corner_nodes(model, set);
  const Eigen::Vector3d n0 = set.normals.front();
  for (std::size_t i = 0; i < set.normals.size(); ++i)
    if (set.normals[i].cross(n0).norm() > kParallel)
      throw InputError("SOFA export: sliding node set '" + set.name + "' (" + set.selection +
                       ") is curved: its normals are not all parallel (node " + std::to_string(set.nodes[i] + 1) +
                       "), and SOFA's PlaneProjectiveConstraint holds one plane; make it fixed or planar");
  p.normal = n0;
  if (p.corners.empty()) return p;
  p.origin_mm = model.nodes[p.corners.front()];
  Eigen::Vector3d lo = model.nodes.front(), hi = lo;
  for (const Eigen::Vector3d& x : model.nodes) {
    lo = lo.cwiseMin(x);
    hi = hi.cwiseMax(x);
  }
  const double tolerance_mm = 1e-6 * std::max((hi - lo).norm(), 1.0);
  for (int c : p.corners)
    if (std::abs((model.nodes[c] - p.origin_mm).dot(n0)) > tolerance_mm)
      throw InputError("SOFA export: sliding node set '" + set.name + "' (" + set.selection +
                       ") is not planar: node " + std::to_string(c + 1) +
                       " lies off the plane of the others, and SOFA's PlaneProjectiveConstraint holds one plane");
  return p;
}

std::string ints(const std::vector<int>& v) {
  std::string out;
  for (std::size_t i = 0; i < v.size(); ++i) {
    if (i > 0) out += ' ';
    out += std::to_string(v[i]);
  }
  return out;
}

struct ForceField {
  std::string material;       // SOFA materialName
  std::string parameter_set;  // in SOFA's order, model stress unit
};

ForceField force_field(const Model& model, std::size_t tissue) {
  const MaterialSpec& m = model.materials[tissue];
  auto stress = [&](double pa) { return shortest_decimal(stress_from_pascal(model.units, pa)); };
  switch (m.law) {
    case MaterialLaw::CompressibleNeoHookean:  // exact: mu/2 (I1-3) - mu lnJ + lambda/2 (lnJ)^2
      return {"NeoHookean", stress(m.mu_Pa) + " " + stress(m.lambda_Pa())};
    case MaterialLaw::NeoHookean:  // deviatoric part exact, volumetric K/2 (lnJ)^2
      return {"MooneyRivlin", stress(m.C10_Pa) + " 0 " + stress(m.K_Pa)};
    case MaterialLaw::MooneyRivlin:
      return {"MooneyRivlin", stress(m.C10_Pa) + " " + stress(m.C01_Pa) + " " + stress(m.K_Pa)};
    case MaterialLaw::Ogden:
      break;
  }
  throw InputError("SOFA export: tissue '" + model.tissue_names[tissue] +
                   "' uses the Ogden law, which is not written for SOFA: its Ogden material changed "
                   "parameter order in v25.12 (k0 mu1 alpha1 -> mu1 alpha1 k0) and the earlier one was "
                   "replaced as not working; use neo-hookean or mooney-rivlin for SOFA");
}

}  // namespace

std::vector<std::string> write_sofa(const Model& model, std::ostream& scene, const SofaOptions& options) {
  validate_model(model);  // every writer refuses an invalid model first, also when called directly
  // ---- checks first: nothing is written for a model SOFA cannot take.
  const bool v25 = options.version == "25.06";
  if (!v25 && options.version != "24.06")
    throw InputError("SOFA export: unknown sofa version '" + options.version +
                     "' (known: \"24.06\" for SOFA v24.06-v24.12, \"25.06\" for SOFA v25.06 and later)");
  const std::size_t n_tissues = model.tissue_names.size();
  std::vector<ForceField> fields;
  for (std::size_t t = 0; t < n_tissues; ++t) fields.push_back(force_field(model, t));
  std::vector<SlidingPlane> planes;
  std::vector<std::string> notes;
  for (const NodeSet& s : model.node_sets)
    if (s.constraint == Constraint::Sliding) planes.push_back(sliding_plane(model, s));

  std::vector<std::vector<std::size_t>> tets_of(n_tissues);
  for (std::size_t e = 0; e < model.elements.size(); ++e)
    tets_of[static_cast<std::size_t>(model.tissue_ids[e] - 1)].push_back(e);

  std::vector<std::string> approximated;
  for (std::size_t t = 0; t < n_tissues; ++t)
    if (!tets_of[t].empty() && model.materials[t].law != MaterialLaw::CompressibleNeoHookean)
      approximated.push_back(model.tissue_names[t] + " (" + material_law_name(model.materials[t].law) + ")");
  if (!approximated.empty()) {
    std::string list;
    for (const std::string& a : approximated) list += (list.empty() ? "" : ", ") + a;
    notes.push_back("SOFA: " + list +
                    " written as SOFA MooneyRivlin, whose volumetric energy is K/2 (ln J)^2 instead of "
                    "K/2 (J-1)^2: identical deviatoric response, results differ slightly where volume changes "
                    "(about 0.5% of the displacement at K/mu = 50, docs/formats.md, SOFA)");
  }
  if (model.order == ElementOrder::Quadratic)
    notes.push_back("SOFA: the tet10 model is written as its linear tets (corner nodes only): SOFA's "
                    "hyperelastic tetrahedra are linear");
  for (std::size_t t = 0; t < n_tissues; ++t)
    if (tets_of[t].empty()) notes.push_back("SOFA: tissue '" + model.tissue_names[t] + "' has no elements and is not written");

  // Components in scene order, to derive the RequiredPlugin list from what is actually used.
  std::vector<std::string> used{"StaticSolver", "SparseLDLSolver", "MeshVTKLoader", "TetrahedronSetTopologyContainer",
                                "TetrahedronSetGeometryAlgorithms", "MechanicalObject", "MeshMatrixMass"};
  if (v25) used.insert(used.begin(), "NewtonRaphsonSolver");
  std::vector<std::pair<const NodeSet*, std::vector<int>>> fixed;
  for (const NodeSet& s : model.node_sets) {
    if (s.constraint != Constraint::Fixed) continue;
    fixed.emplace_back(&s, corner_nodes(model, s));
    if (fixed.back().second.empty()) {
      notes.push_back("SOFA: fixed set '" + s.name + "' has no corner node and is not written");
      fixed.pop_back();
    }
  }
  if (!fixed.empty()) used.push_back("FixedProjectiveConstraint");
  planes.erase(std::remove_if(planes.begin(), planes.end(),
                              [&](const SlidingPlane& p) {
                                if (!p.corners.empty()) return false;
                                notes.push_back("SOFA: sliding set '" + p.set->name + "' has no corner node and is not written");
                                return true;
                              }),
               planes.end());
  if (!planes.empty()) used.push_back("PlaneProjectiveConstraint");
  used.push_back("TetrahedronHyperelasticityFEMForceField");
  std::vector<std::string> plugins;
  for (const std::string& c : used)
    if (std::find(plugins.begin(), plugins.end(), plugin_of(c)) == plugins.end()) plugins.push_back(plugin_of(c));

  // ---- the scene
  const UnitSystem u = model.units;
  std::ostringstream out;
  out << "<?xml version=\"1.0\"?>\n";
  out << "<!-- tissuemesh SOFA scene (layout of SOFA v" << options.version
      << (v25 ? " and later" : "-v24.12") << ")" << (model.title.empty() ? "" : ": " + xml_comment(model.title))
      << " -->\n";
  out << "<!-- units " << unit_system_name(u) << ": length " << length_unit(u) << ", stress " << stress_unit(u)
      << ", density " << density_unit(u) << ", acceleration " << acceleration_unit(u)
      << "; coordinates LPS; indices 0-based -->\n";
  const Eigen::Vector3d g(acceleration_from_m_per_s2(u, model.gravity.acceleration_m_s2.x()),
                          acceleration_from_m_per_s2(u, model.gravity.acceleration_m_s2.y()),
                          acceleration_from_m_per_s2(u, model.gravity.acceleration_m_s2.z()));
  out << "<Node name=\"root\" dt=\"1\" gravity=\"" << vec3(g) << "\">\n";
  for (const std::string& p : plugins) out << "  <RequiredPlugin pluginName=\"" << p << "\"/>\n";
  out << "  <DefaultAnimationLoop/>\n";
  out << "  <Node name=\"breast\">\n";
  const AnalysisSettings& a = model.analysis;
  if (v25) {
    // Absolute residual threshold 0 = off: an absolute force norm depends on the unit system.
    out << "    <NewtonRaphsonSolver name=\"newton\" maxNbIterationsNewton=\"" << a.max_newton_iterations
        << "\" maxNbIterationsLineSearch=\"5\" relativeInitialStoppingThreshold=\"" << shortest_decimal(a.residual_tolerance)
        << "\" absoluteResidualStoppingThreshold=\"0\"/>\n";
    out << "    <StaticSolver name=\"static\" newtonSolver=\"@newton\"/>\n";
  } else {
    // Thresholds <= 0 are off in v24 StaticSolver; the absolute ones depend on the unit system.
    out << "    <StaticSolver name=\"static\" newton_iterations=\"" << a.max_newton_iterations
        << "\" relative_correction_tolerance_threshold=\"" << shortest_decimal(a.displacement_tolerance)
        << "\" relative_residual_tolerance_threshold=\"" << shortest_decimal(a.residual_tolerance)
        << "\" absolute_correction_tolerance_threshold=\"0\" absolute_residual_tolerance_threshold=\"0\"/>\n";
  }
  out << "    <SparseLDLSolver name=\"linear_solver\" template=\"CompressedRowSparseMatrixMat3x3d\"/>\n";
  out << "    <MeshVTKLoader name=\"loader\" filename=\"" << xml_escape(options.mesh_file) << "\"/>\n";
  out << "    <TetrahedronSetTopologyContainer name=\"topology\" src=\"@loader\"/>\n";
  out << "    <TetrahedronSetGeometryAlgorithms name=\"geometry\" template=\"Vec3d\"/>\n";
  out << "    <MechanicalObject name=\"dofs\" template=\"Vec3d\" src=\"@loader\"/>\n";
  out << "    <!-- massDensity: one value per tetrahedron (" << density_unit(u) << ") -->\n";
  out << "    <MeshMatrixMass name=\"mass\" topology=\"@topology\" massDensity=\"";
  std::vector<std::string> density(n_tissues);
  for (std::size_t t = 0; t < n_tissues; ++t) density[t] = shortest_decimal(density_from_kg_per_m3(u, model.materials[t].density_kg_m3));
  for (std::size_t e = 0; e < model.elements.size(); ++e)
    out << (e > 0 ? " " : "") << density[static_cast<std::size_t>(model.tissue_ids[e] - 1)];
  out << "\"/>\n";
  for (const auto& [set, corners] : fixed) {
    out << "    <!-- fixed set " << set->name << ": " << xml_comment(set->selection) << " -->\n";
    out << "    <FixedProjectiveConstraint name=\"fixed_" << set->name << "\" indices=\"" << ints(corners) << "\"/>\n";
  }
  for (const SlidingPlane& p : planes) {
    const Eigen::Vector3d origin = p.origin_mm * length_from_mm(u, 1.0);  // as write_legacy_vtk
    out << "    <!-- sliding set " << p.set->name << ": " << xml_comment(p.set->selection) << " (n . u = 0) -->\n";
    out << "    <PlaneProjectiveConstraint name=\"sliding_" << p.set->name << "\" indices=\"" << ints(p.corners)
        << "\" origin=\"" << vec3(origin) << "\" normal=\"" << vec3(p.normal) << "\"/>\n";
  }
  for (std::size_t t = 0; t < n_tissues; ++t) {
    if (tets_of[t].empty()) continue;
    out << "    <!-- " << model.tissue_names[t] << ": " << material_law_name(model.materials[t].law)
        << ", ParameterSet in " << stress_unit(u) << " -->\n";
    out << "    <Node name=\"" << model.tissue_names[t] << "\">\n";
    out << "      <TetrahedronSetTopologyContainer name=\"t\" tetrahedra=\"";
    bool first = true;
    for (std::size_t e : tets_of[t])
      for (int k = 0; k < 4; ++k) {
        out << (first ? "" : " ") << model.elements[e][k];
        first = false;
      }
    out << "\"/>\n";
    out << "      <TetrahedronHyperelasticityFEMForceField name=\"material\" topology=\"@t\" materialName=\""
        << fields[t].material << "\" ParameterSet=\"" << fields[t].parameter_set << "\"/>\n";
    out << "    </Node>\n";
  }
  out << "  </Node>\n";
  out << "</Node>\n";
  scene << out.str();
  return notes;
}

}  // namespace tissuemesh
