// Why, for the choices that follow FEBio's source rather than its manual:
// - Element ids are contiguous in block order: the 4.0 reader keeps the file's ids
//   (FEBioMeshDomainsSection4.cpp, el.SetID(domElement.id)), but FEBModel::BuildPart with
//   buildDomains (other FEBio import paths) renumbers elements 1, 2, ... in file order, ignoring
//   them. Ids that increase within and across blocks without gaps are the same under both, so plot
//   and log element ids never depend on the reader path.
// - Names of at most 127 characters, ASCII comments without "--": FEBio's XMLReader copies
//   attribute values into 128-character buffers and does not expand entities
//   (FEBioXML/XMLReader.h/.cpp).
// - Oblique sliding nodes: FEBio's `<bc type="linear constraint">` sets parent dof = sum value_j *
//   child dof_j, offset 0 (FEBioXML/FEBioBoundarySection3.cpp ParseLinearConstraint,
//   FECore/FELinearConstraintManager.cpp Update), and FELinearConstraintManager::Activate refuses
//   a parent dof that is a child or a fixed dof. So the node's normals from all its oblique sets,
//   less the dofs that axis-parallel sets fix, are reduced by complete pivoting, and each
//   independent row gives one constraint whose parent is its pivot dof (largest coefficient).
#include "fe_export/febio/write_febio.h"

#include "fe_export/text_format.h"

#include "core/errors.h"
#include "core/node_ordering.h"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <map>
#include <set>
#include <sstream>

namespace tissuemesh {

namespace {

// ---------------------------------------------------------------------------------------------
// Text helpers

void comment(std::ostream& out, const std::string& indent, const std::string& text) {
  out << indent << "<!-- " << xml_comment(text) << " -->\n";
}

/// FEBio's XMLReader copies attribute values into char[MAX_TAG = 128] buffers without a bounds
/// check (FEBioXML/XMLReader.h), so every attribute value must stay below 128 characters.
constexpr std::size_t kMaxAttribute = 127;

/// A file name from the model title: [A-Za-z0-9_.-] kept, anything else '_'; "model" if empty.
std::string file_stem(const std::string& title) {
  std::string out;
  for (char c : title) {
    const bool keep = (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_' ||
                      c == '.' || c == '-';
    out += keep ? c : '_';
  }
  if (out.find_first_not_of("_.") == std::string::npos) return "model";
  return out.substr(0, kMaxAttribute - 28);  // room for "_disp.txt"
}

/// Comma-separated 1-based ids, 16 per line.
void id_list(std::ostream& out, const std::vector<int>& ids0, const std::string& indent) {
  for (std::size_t i = 0; i < ids0.size(); ++i) {
    if (i % 16 == 0) out << '\n' << indent;
    out << ids0[i] + 1 << (i + 1 < ids0.size() ? (i % 16 == 15 ? "," : ", ") : "");
  }
  out << '\n';
}

const char* kDof[3] = {"x", "y", "z"};

// ---------------------------------------------------------------------------------------------
// Sections

void write_control(std::ostream& out, const AnalysisSettings& a, const FebioOptions& options) {
  const double dt = 1.0 / a.load_steps;
  out << "  <Control>\n"
      << "    <analysis>STATIC</analysis>\n"
      << "    <time_steps>" << a.load_steps << "</time_steps>\n"
      << "    <step_size>" << shortest_decimal(dt) << "</step_size>\n"
      << "    <plot_level>PLOT_MAJOR_ITRS</plot_level>\n"
      << "    <output_level>OUTPUT_MAJOR_ITRS</output_level>\n"
      << "    <time_stepper type=\"default\">\n"
      << "      <max_retries>5</max_retries>\n"
      << "      <opt_iter>10</opt_iter>\n"
      << "      <dtmin>" << shortest_decimal(a.min_step_fraction) << "</dtmin>\n"
      << "      <dtmax>" << shortest_decimal(dt) << "</dtmax>\n"
      << "    </time_stepper>\n"
      << "    <solver type=\"solid\">\n"
      << "      <symmetric_stiffness>symmetric</symmetric_stiffness>\n"
      << "      <max_refs>" << a.max_newton_iterations << "</max_refs>\n"
      << "      <dtol>" << shortest_decimal(a.displacement_tolerance) << "</dtol>\n"
      << "      <etol>" << shortest_decimal(a.energy_tolerance) << "</etol>\n"
      << "      <rtol>" << shortest_decimal(a.residual_tolerance) << "</rtol>\n"
      << "      <qn_method type=\"BFGS\">\n"
      << "        <max_ups>0</max_ups>\n"  // full Newton: the stiffness is reformed every iteration
      << "      </qn_method>\n";
  if (!options.linear_solver.empty())
    out << "      <linear_solver type=\"" << xml_escape(options.linear_solver) << "\"/>\n";
  out << "    </solver>\n"
      << "  </Control>\n";
}

void write_material(std::ostream& out, int id, const std::string& tissue, const MaterialSpec& m, UnitSystem u) {
  const std::string su = stress_unit(u);
  auto stress = [&](double pa) { return shortest_decimal(stress_from_pascal(u, pa)); };
  const char* type = m.law == MaterialLaw::Ogden                    ? "Ogden"
                     : m.law == MaterialLaw::CompressibleNeoHookean ? "neo-Hookean"
                                                                    : "Mooney-Rivlin";
  std::ostringstream what;
  what << tissue << ": " << material_law_name(m.law) << ", mu = " << shortest_decimal(m.mu_Pa) << " Pa, K = " << shortest_decimal(m.K_Pa)
       << " Pa, density " << shortest_decimal(m.density_kg_m3) << " kg/m^3 (written in " << su << ", "
       << density_unit(u) << "); source: " << (m.source.empty() ? "not given" : m.source);
  comment(out, "    ", what.str());
  out << "    <material id=\"" << id << "\" name=\"" << xml_escape(tissue) << "\" type=\"" << type << "\">\n"
      << "      <density>" << shortest_decimal(density_from_kg_per_m3(u, m.density_kg_m3)) << "</density>\n";
  switch (m.law) {
    case MaterialLaw::NeoHookean:
    case MaterialLaw::MooneyRivlin:
      out << "      <c1>" << stress(m.C10_Pa) << "</c1>\n"
          << "      <c2>" << (m.law == MaterialLaw::NeoHookean ? std::string("0") : stress(m.C01_Pa)) << "</c2>\n";
      break;
    case MaterialLaw::Ogden:
      for (std::size_t i = 0; i < m.ogden.size(); ++i)
        out << "      <c" << i + 1 << ">" << stress(2.0 * m.ogden[i].mu_Pa) << "</c" << i + 1 << ">\n";
      for (std::size_t i = 0; i < m.ogden.size(); ++i)
        out << "      <m" << i + 1 << ">" << shortest_decimal(m.ogden[i].alpha) << "</m" << i + 1 << ">\n";
      break;
    case MaterialLaw::CompressibleNeoHookean:
      out << "      <E>" << stress(m.young_modulus_Pa()) << "</E>\n"
          << "      <v>" << shortest_decimal(m.poisson_ratio()) << "</v>\n";
      break;
  }
  if (m.law != MaterialLaw::CompressibleNeoHookean)
    out << "      <k>" << stress(m.K_Pa) << "</k>\n"
        << "      <pressure_model>Abaqus</pressure_model>\n";  // U = K/2 (J-1)^2, as Abaqus/CalculiX
  out << "    </material>\n";
}

/// Elements of each tissue (0-based tissue index), in model order.
std::vector<std::vector<int>> elements_by_tissue(const Model& model) {
  std::vector<std::vector<int>> by(model.tissue_names.size());
  for (std::size_t e = 0; e < model.elements.size(); ++e) by[model.tissue_ids[e] - 1].push_back(static_cast<int>(e));
  return by;
}

// One FEBio linear constraint: parent dof = sum value * child dof (same node).
struct LinearConstraint {
  int node = 0;
  int parent = 0;
  std::vector<std::pair<int, double>> children;
};

/// Sliding sets: which are written as single-dof `zero displacement` (axis -> 0..2, else -1) and
/// the linear constraints of all other sliding nodes (see the header).
struct SlidingPlan {
  std::vector<int> axis;                  // per node set (-1 for fixed or oblique sets)
  std::vector<LinearConstraint> constraints;
  std::map<std::string, int> per_set;     // oblique set -> nodes constrained
};

SlidingPlan plan_sliding(const Model& model) {
  const std::size_t n_nodes = model.nodes.size();
  SlidingPlan plan;
  plan.axis.assign(model.node_sets.size(), -1);
  std::vector<char> fixed(n_nodes, 0);
  std::vector<std::array<char, 3>> fixed_dof(n_nodes, {0, 0, 0});
  for (std::size_t s = 0; s < model.node_sets.size(); ++s) {
    const NodeSet& set = model.node_sets[s];
    if (set.constraint == Constraint::Fixed) {
      for (int v : set.nodes) fixed[v] = 1;
      continue;
    }
    for (int i = 0; i < 3; ++i)
      if (std::all_of(set.normals.begin(), set.normals.end(),
                      [&](const Eigen::Vector3d& n) { return std::abs(n[i]) > 1.0 - 1e-9; }))
        plan.axis[s] = i;
    if (plan.axis[s] >= 0)
      for (int v : set.nodes) fixed_dof[v][plan.axis[s]] = 1;
  }
  std::map<int, std::vector<Eigen::Vector3d>> normals;  // ordered by node: deterministic output
  std::map<int, std::set<std::string>> sets_of;
  for (std::size_t s = 0; s < model.node_sets.size(); ++s) {
    const NodeSet& set = model.node_sets[s];
    if (set.constraint != Constraint::Sliding || plan.axis[s] >= 0) continue;
    for (std::size_t k = 0; k < set.nodes.size(); ++k)
      if (!fixed[set.nodes[k]]) {
        normals[set.nodes[k]].push_back(set.normals[k]);
        sets_of[set.nodes[k]].insert(set.name);
      }
  }
  for (auto& [node, rows] : normals) {
    // Complete pivoting on the rows restricted to the dofs no axis set fixes.
    for (auto& r : rows)
      for (int j = 0; j < 3; ++j)
        if (fixed_dof[node][j]) r[j] = 0.0;
    std::array<char, 3> used{0, 0, 0};
    for (int j = 0; j < 3; ++j) used[j] = fixed_dof[node][j];
    std::vector<std::pair<std::size_t, int>> pivots;  // (row, column)
    for (std::size_t rank = 0; rank < rows.size(); ++rank) {
      std::size_t br = rank;
      int bc = -1;
      double best = 1e-9;  // rows are unit normals: anything smaller is a dependent row
      for (std::size_t r = rank; r < rows.size(); ++r)
        for (int j = 0; j < 3; ++j)
          if (!used[j] && std::abs(rows[r][j]) > best) best = std::abs(rows[r][j]), br = r, bc = j;
      if (bc < 0) break;
      std::swap(rows[rank], rows[br]);
      rows[rank] /= rows[rank][bc];
      for (std::size_t r = 0; r < rows.size(); ++r) {
        const double factor = rows[r][bc];
        if (r != rank) rows[r] -= factor * rows[rank];
      }
      used[bc] = 1;
      pivots.emplace_back(rank, bc);
    }
    for (const auto& [r, c] : pivots) {
      LinearConstraint lc;
      lc.node = node;
      lc.parent = c;
      for (int j = 0; j < 3; ++j) {
        const bool child = !fixed_dof[node][j] &&
                           std::none_of(pivots.begin(), pivots.end(), [&](const auto& p) { return p.second == j; });
        if (child && std::abs(rows[r][j]) > 1e-14) lc.children.emplace_back(j, -rows[r][j]);
      }
      plan.constraints.push_back(lc);
    }
    if (!pivots.empty())
      for (const std::string& name : sets_of[node]) ++plan.per_set[name];
  }
  return plan;
}

void write_boundary(std::ostream& out, const Model& model, const SlidingPlan& plan) {
  if (model.node_sets.empty()) {  // FEBioBoundarySection3::Parse accepts an empty leaf
    out << "  <Boundary/>\n";
    return;
  }
  out << "  <Boundary>\n";
  for (std::size_t s = 0; s < model.node_sets.size(); ++s) {
    const NodeSet& set = model.node_sets[s];
    const bool fixed = set.constraint == Constraint::Fixed;
    if (!fixed && plan.axis[s] < 0) continue;
    if (fixed) comment(out, "    ", "fixed set '" + set.name + "' (" + set.selection + "): u = 0");
    else
      comment(out, "    ", "sliding set '" + set.name + "' (" + set.selection + "): every normal is along " +
                              kDof[plan.axis[s]] + ", so n.u = 0 is u" + kDof[plan.axis[s]] + " = 0");
    out << "    <bc name=\"" << xml_escape(set.name) << "\" node_set=\"" << xml_escape(set.name)
        << "\" type=\"zero displacement\">\n";
    for (int i = 0; i < 3; ++i)
      out << "      <" << kDof[i] << "_dof>" << (fixed || plan.axis[s] == i ? 1 : 0) << "</" << kDof[i] << "_dof>\n";
    out << "    </bc>\n";
  }
  if (!plan.constraints.empty()) {
    std::string names;
    for (const auto& [name, count] : plan.per_set) names += (names.empty() ? "" : ", ") + name;
    comment(out, "    ", "sliding sets " + names +
                              ": n.u = 0 per node as linear constraints, parent dof = sum value * child dof "
                              "(same node); nodes of fixed sets are left to those");
  }
  for (const LinearConstraint& lc : plan.constraints) {
    out << "    <bc type=\"linear constraint\">\n"
        << "      <node>" << lc.node + 1 << "</node>\n"
        << "      <dof>" << kDof[lc.parent] << "</dof>\n";
    for (const auto& [dof, value] : lc.children)
      out << "      <child_dof>\n"
          << "        <node>" << lc.node + 1 << "</node>\n"
          << "        <dof>" << kDof[dof] << "</dof>\n"
          << "        <value>" << shortest_decimal(value) << "</value>\n"
          << "      </child_dof>\n";
    out << "    </bc>\n";
  }
  out << "  </Boundary>\n";
}

void write_loads(std::ostream& out, const Model& model) {
  const UnitSystem u = model.units;
  const Eigen::Vector3d& g = model.gravity.acceleration_m_s2;
  Eigen::Vector3d a;
  for (int i = 0; i < 3; ++i) a[i] = acceleration_from_m_per_s2(u, g[i]);
  std::ostringstream c;
  c << "gravity '" << model.gravity.name << "' = (" << shortest_decimal(a[0]) << ", " << shortest_decimal(a[1]) << ", " << shortest_decimal(a[2]) << ") "
    << acceleration_unit(u)
    << " (LPS). FEBio's const body_load is the NEGATIVE of the acceleration field: the solid domain "
       "assembles -rho*b into the external force (docs/formats.md, FEBio; checked against CalculiX by a run), so the "
       "vector below is minus the gravity";
  out << "  <Loads>\n";
  comment(out, "    ", c.str());
  out << "    <body_load type=\"const\">\n";
  for (int i = 0; i < 3; ++i)
    out << "      <" << kDof[i] << " lc=\"1\">" << shortest_decimal(-a[i]) << "</" << kDof[i] << ">\n";
  out << "    </body_load>\n"
      << "  </Loads>\n";
}

std::vector<std::string> collect_notes(const Model& model, const FebioOptions& options, const SlidingPlan& plan,
                                       const std::vector<std::vector<int>>& by_tissue) {
  std::vector<std::string> notes;
  for (std::size_t t = 0; t < by_tissue.size(); ++t)
    if (by_tissue[t].empty())
      notes.push_back("FEBio: tissue '" + model.tissue_names[t] +
                      "' has no elements; its material is written but no Elements block or domain");
  bool grouped = true;
  for (std::size_t e = 1; e < model.tissue_ids.size(); ++e) grouped = grouped && model.tissue_ids[e] >= model.tissue_ids[e - 1];
  if (!grouped)
    notes.push_back("FEBio: elements are numbered 1.." + std::to_string(model.elements.size()) +
                    " tissue by tissue, so FEBio element ids differ from the model's element order "
                    "(febio_element_ids gives the map)");
  if (model.order == ElementOrder::Linear) {
    double worst = 0.0;
    std::string who;
    for (std::size_t t = 0; t < model.materials.size(); ++t)
      if (model.materials[t].K_Pa / model.materials[t].mu_Pa > worst)
        worst = model.materials[t].K_Pa / model.materials[t].mu_Pa, who = model.tissue_names[t];
    if (worst >= 10.0)
      notes.push_back("FEBio: tet4 with nearly incompressible tissue ('" + who + "', K/mu = " + shortest_decimal(std::round(worst)) +
                      ") locks (too stiff); prefer tet10, or a SolidDomain type=\"ut4-solid\" / "
                      "\"three-field-solid\" (FEBio User's Manual 4, MeshDomains section)");
  }
  const std::string solver = options.linear_solver;
  if ((solver.empty() || solver == "skyline") && model.nodes.size() >= 10000) {
    const long long profile =
        matrix_profile(static_cast<int>(model.nodes.size()), model.elements, model.nodes_per_element());
    std::ostringstream s;
    s << "FEBio: built without MKL, FEBio uses the skyline solver" << (solver.empty() ? " by default" : "")
      << ", whose memory and time grow with the matrix profile (here " << profile
      << " node columns, x9 for dofs); model.node_order: rcm (the default) keeps it small for tet4, "
         "tet10 keeps its corner nodes first and stays large; an MKL build (pardiso) avoids the issue";
    notes.push_back(s.str());
  }
  if (solver == "pardiso" || solver == "pardiso_64" || solver == "mkl_dss" || solver == "fgmres" || solver == "cg")
    notes.push_back("FEBio: linear_solver '" + solver + "' exists only in FEBio builds with Intel MKL");
  if (model.node_sets.empty())
    notes.push_back("FEBio: the model has no fixed or sliding node set: rigid-body motion is free and the solve "
                    "will fail");
  for (const auto& [name, count] : plan.per_set)
    notes.push_back("FEBio: sliding set '" + name + "' is not axis-aligned: written as linear constraints n.u = 0 at " +
                    std::to_string(count) + " nodes");
  return notes;
}

}  // namespace

std::vector<int> febio_element_ids(const Model& model) {
  std::vector<int> ids(model.elements.size(), 0);
  int next = 1;
  for (const std::vector<int>& els : elements_by_tissue(model))
    for (int e : els) ids[e] = next++;
  return ids;
}

std::vector<std::string> write_febio(const Model& model, std::ostream& out, const FebioOptions& options) {
  validate_model(model);
  for (const NodeSet& s : model.node_sets)
    if (s.name == "all")
      throw InputError("FEBio export: node set name 'all' is reserved for the file's Nodes block; rename the set");
  std::vector<std::string> names = model.tissue_names;
  for (const NodeSet& s : model.node_sets) names.push_back(s.name);
  for (const FaceSet& s : model.face_sets) names.push_back(s.name);
  for (const std::string& name : names)
    if (name.size() > kMaxAttribute)
      throw InputError("FEBio export: name '" + name.substr(0, 40) + "...' has " + std::to_string(name.size()) +
                       " characters; FEBio reads at most " + std::to_string(kMaxAttribute) + " per attribute");
  const UnitSystem u = model.units;
  const int npe = model.nodes_per_element();
  const auto by_tissue = elements_by_tissue(model);
  const std::vector<int> elem_id = febio_element_ids(model);
  const SlidingPlan plan = plan_sliding(model);

  out << "<?xml version=\"1.0\" encoding=\"ISO-8859-1\"?>\n";
  comment(out, "",
          "tissuemesh model '" + model.title + "': " + std::to_string(model.nodes.size()) + " nodes, " +
              std::to_string(model.elements.size()) + (npe == 4 ? " tet4" : " tet10") + " elements; units " +
              unit_system_name(u) + " (length " + length_unit(u) + ", stress " + stress_unit(u) + ", density " +
              density_unit(u) + ", acceleration " + acceleration_unit(u) + ")");
  out << "<febio_spec version=\"4.0\">\n"
      << "  <Module type=\"solid\"/>\n";
  write_control(out, model.analysis, options);

  out << "  <Material>\n";
  for (std::size_t t = 0; t < model.tissue_names.size(); ++t)
    write_material(out, static_cast<int>(t) + 1, model.tissue_names[t], model.materials[t], u);
  out << "  </Material>\n";

  out << "  <Mesh>\n"
      << "    <Nodes name=\"all\">\n";
  for (std::size_t i = 0; i < model.nodes.size(); ++i) {
    const Eigen::Vector3d& p = model.nodes[i];
    out << "      <node id=\"" << i + 1 << "\">" << shortest_decimal(length_from_mm(u, p[0])) << ',' << shortest_decimal(length_from_mm(u, p[1]))
        << ',' << shortest_decimal(length_from_mm(u, p[2])) << "</node>\n";
  }
  out << "    </Nodes>\n";
  for (std::size_t t = 0; t < by_tissue.size(); ++t) {
    if (by_tissue[t].empty()) continue;
    out << "    <Elements type=\"" << (npe == 4 ? "tet4" : "tet10") << "\" name=\"" << xml_escape(model.tissue_names[t])
        << "\">\n";
    for (int e : by_tissue[t]) {
      out << "      <elem id=\"" << elem_id[e] << "\">";
      for (int k = 0; k < npe; ++k) out << (k ? "," : "") << model.elements[e][k] + 1;
      out << "</elem>\n";
    }
    out << "    </Elements>\n";
  }
  for (const NodeSet& s : model.node_sets) {
    out << "    <NodeSet name=\"" << xml_escape(s.name) << "\">";
    id_list(out, s.nodes, "      ");
    out << "    </NodeSet>\n";
  }
  for (const FaceSet& s : model.face_sets) {
    out << "    <Surface name=\"" << xml_escape(s.name) << "\">\n";
    int id = 1;
    for (const auto& [e, f] : s.faces) {
      const auto& el = model.elements[e];
      out << "      <" << (npe == 4 ? "tri3" : "tri6") << " id=\"" << id++ << "\">";
      int k = 0;
      for (int c : face_corners(f)) out << (k++ ? "," : "") << el[c] + 1;
      if (npe == 10)
        for (int m : face_midsides(f)) out << ',' << el[m] + 1;
      out << "</" << (npe == 4 ? "tri3" : "tri6") << ">\n";
    }
    out << "    </Surface>\n";
  }
  out << "  </Mesh>\n";

  out << "  <MeshDomains>\n";
  for (std::size_t t = 0; t < by_tissue.size(); ++t)
    if (!by_tissue[t].empty())
      out << "    <SolidDomain name=\"" << xml_escape(model.tissue_names[t]) << "\" mat=\""
          << xml_escape(model.tissue_names[t]) << "\"/>\n";
  out << "  </MeshDomains>\n";

  write_boundary(out, model, plan);
  write_loads(out, model);

  out << "  <LoadData>\n"
      << "    <load_controller id=\"1\" name=\"ramp\" type=\"loadcurve\">\n"
      << "      <interpolate>LINEAR</interpolate>\n"
      << "      <extend>CONSTANT</extend>\n"
      << "      <points>\n"
      << "        <pt>0,0</pt>\n"
      << "        <pt>1,1</pt>\n"
      << "      </points>\n"
      << "    </load_controller>\n"
      << "  </LoadData>\n";

  out << "  <Output>\n"
      << "    <plotfile type=\"febio\">\n"
      << "      <var type=\"displacement\"/>\n"
      << "      <var type=\"stress\"/>\n"
      << "    </plotfile>\n"
      << "    <logfile>\n"
      << "      <node_data data=\"ux;uy;uz\" file=\"" << xml_escape(file_stem(model.title) + "_disp.txt")
      << "\" delim=\",\"/>\n"
      << "    </logfile>\n"
      << "  </Output>\n"
      << "</febio_spec>\n";
  return collect_notes(model, options, plan, by_tissue);
}

}  // namespace tissuemesh
