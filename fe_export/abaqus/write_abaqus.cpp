// Why: the deck is checked with CalculiX 2.20 (the tests run it), whose reader is stricter than
// Abaqus' in places; each rule below answers a CalculiX behaviour seen in runs.
// - Reals: ccx reads each field as f20.0 of its first 20 characters and silently cuts the rest
//   (a 25-character "0.2000...e+01" was read as 0.2), so no real is longer than 20 characters.
// - Ogden N >= 2: ccx replaces any D_i < 1e-10 by (0.1/mu)^i (hyperelastics.f), a unit-dependent
//   (J-1)^4 term, so D2 (, D3) are written as D1 * 1e12 instead of 0: below 1e-12 of the (J-1)^2
//   term for |J-1| <= 1.
// - Sliding nodes also in a fixed set get no *EQUATION and stay fixed: ccx refuses a DOF both
//   fixed and dependent (exit 201, "dependent side of a MPC and a SPC"). A node in two sliding sets
//   uses a different dependent DOF per equation (ccx refuses a DOF dependent twice); parallel
//   duplicates are dropped, with a note.
// - Tissues without elements are left out: an empty ELSET makes *SOLID SECTION fail.
// ccx's RF (printed with TOTALS=YES) is the internal force at the fixed nodes: it leaves out the
// share of the body load lumped on those nodes, so the RF total is the weight less that share
// (docs/formats.md, "Abaqus / CalculiX").
#include "fe_export/abaqus/write_abaqus.h"

#include "core/errors.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <map>
#include <set>
#include <sstream>

namespace tissuemesh {

namespace {

// CalculiX reads every real with `read(textpart(i)(1:20),'(f20.0)')`: a field longer than 20
// characters is cut silently. The shortest round-trip form fits for ordinary values; otherwise
// (e.g. -1.2345678901234567e-05) the precision is lowered until it fits (still >= 13 digits).
constexpr std::size_t kMaxRealChars = 20;
// At most 16 entries per data line (CalculiX splits a line into at most 16 fields).
constexpr std::size_t kMaxEntries = 16;
// CalculiX stores set names in 81 characters and appends one ('N', 'E', ...) internally.
constexpr std::size_t kMaxNameChars = 80;
// CalculiX replaces a compressibility coefficient below 1e-10 (absolute) by (0.1/mu)^i
// (hyperelastics.f); Ogden D2, D3 are therefore written as D1 * kHigherOrderD instead of 0:
// (J-1)^(2i)/D_i is then at most 1e-12 of (J-1)^2/D1 for |J-1| <= 1, i.e. nothing.
constexpr double kCalculixMinD = 1e-10;
constexpr double kHigherOrderD = 1e12;

std::string real(double v) {
  if (v == 0.0 || !std::isfinite(v)) return "0";  // finiteness is checked by validate_model
  char buf[64];
  auto r = std::to_chars(buf, buf + sizeof buf, v);
  std::string s(buf, r.ptr);
  for (int precision = 16; s.size() > kMaxRealChars && precision > 0; --precision) {
    r = std::to_chars(buf, buf + sizeof buf, v, std::chars_format::general, precision);
    s.assign(buf, r.ptr);
  }
  return s;
}

/// Writes `entries` as data lines of at most kMaxEntries entries.
void write_list(std::ostream& out, const std::vector<std::string>& entries) {
  for (std::size_t i = 0; i < entries.size(); ++i) {
    out << entries[i];
    out << ((i + 1 == entries.size() || (i + 1) % kMaxEntries == 0) ? "\n" : ", ");
  }
}

void write_ids(std::ostream& out, const std::vector<int>& zero_based) {
  std::vector<std::string> entries;
  entries.reserve(zero_based.size());
  for (int i : zero_based) entries.push_back(std::to_string(i + 1));
  write_list(out, entries);
}

/// One line of comment or heading text: no line breaks, cannot start a keyword.
std::string one_line(const std::string& text) {
  std::string s;
  for (char c : text) s += (c == '\n' || c == '\r' || c == '\t') ? ' ' : c;
  while (!s.empty() && (s.front() == '*' || s.front() == ' ')) s.erase(s.begin());
  return s;
}

struct Names {
  std::vector<std::string> tissue;          // per tissue: element set (upper-case)
  std::vector<std::string> node_set;        // per node set
  std::vector<std::string> face_set;        // per face set: surface name
};

Names check_names(const Model& model) {
  Names n;
  std::set<std::string> elsets{"EALL"}, nsets{"NALL"}, surfaces;
  auto add = [](std::set<std::string>& used, const std::string& name, const std::string& what) {
    if (name.size() + 2 > kMaxNameChars)  // +2: the M_ of materials, the _S1 suffix is checked below
      throw InputError("abaqus: " + what + " name '" + name + "' is longer than " +
                       std::to_string(kMaxNameChars - 2) + " characters (CalculiX limit)");
    if (!used.insert(name).second)
      throw InputError("abaqus: " + what + " name '" + name +
                       "' clashes with another set once upper-cased (Abaqus/CalculiX names are not "
                       "case-sensitive; EALL and NALL are reserved)");
  };
  for (const std::string& t : model.tissue_names) {
    n.tissue.push_back(abaqus_name(t));
    add(elsets, n.tissue.back(), "tissue");
  }
  for (const NodeSet& s : model.node_sets) {
    n.node_set.push_back(abaqus_name(s.name));
    add(nsets, n.node_set.back(), "node set");
  }
  for (const FaceSet& s : model.face_sets) {
    n.face_set.push_back(abaqus_name(s.name));
    add(surfaces, n.face_set.back(), "face set");
    for (int f = 1; f <= 4; ++f) add(elsets, n.face_set.back() + "_S" + std::to_string(f), "face set");
  }
  return n;
}

void check_materials(const Model& model) {
  for (std::size_t t = 0; t < model.materials.size(); ++t)
    if (model.materials[t].law == MaterialLaw::CompressibleNeoHookean)
      throw InputError("abaqus: tissue '" + model.tissue_names[t] +
                       "' uses compressible-neo-hookean, which has no exact Abaqus/CalculiX "
                       "equivalent (Abaqus NEO HOOKE is the uncoupled form): use neo-hookean "
                       "(uncoupled) for Abaqus/CalculiX");
}

void write_material(std::ostream& out, const std::string& name, const MaterialSpec& m, UnitSystem units,
                    std::vector<std::string>& notes) {
  auto stress = [&](double pa) { return stress_from_pascal(units, pa); };
  const double D1 = 2.0 / stress(m.K_Pa);
  if (D1 < kCalculixMinD)
    notes.push_back("tissue " + name + ": D1 = " + real(D1) +
                    " is below 1e-10, which CalculiX replaces by its default (K = 20 mu); use another unit system");
  out << "*MATERIAL, NAME=M_" << name << "\n";
  switch (m.law) {
    case MaterialLaw::NeoHookean:
      out << "*HYPERELASTIC, NEO HOOKE\n" << real(stress(m.C10_Pa)) << ", " << real(D1) << "\n";
      break;
    case MaterialLaw::MooneyRivlin:
      out << "*HYPERELASTIC, MOONEY-RIVLIN\n"
          << real(stress(m.C10_Pa)) << ", " << real(stress(m.C01_Pa)) << ", " << real(D1) << "\n";
      break;
    case MaterialLaw::Ogden: {
      const std::size_t n = m.ogden.size();
      out << "*HYPERELASTIC, OGDEN, N=" << n << "\n";
      if (n > 1)
        out << "** D2" << (n > 2 ? ", D3" : "") << " = D1 * 1e12 (not 0: CalculiX would replace 0 by "
            << "(0.1/mu)^i); the (J-1)^4, (J-1)^6 terms are then negligible\n";
      std::vector<std::string> v;
      for (const OgdenTerm& term : m.ogden) {
        v.push_back(real(stress(term.mu_Pa)));
        v.push_back(real(term.alpha));
      }
      for (std::size_t i = 0; i < n; ++i) v.push_back(real(i == 0 ? D1 : D1 * kHigherOrderD));
      // Material data lines hold 8 values (N=3: mu1..alpha3, D1, D2 / D3): CalculiX CrunchiX
      // User's Manual 2.20, *HYPERELASTIC.
      for (std::size_t i = 0; i < v.size(); ++i) out << v[i] << ((i + 1 == v.size() || i == 7) ? "\n" : ", ");
      break;
    }
    case MaterialLaw::CompressibleNeoHookean:
      break;  // refused by check_materials
  }
  out << "*DENSITY\n" << real(density_from_kg_per_m3(units, m.density_kg_m3)) << "\n";
}

/// *EQUATION n . u = 0 for each node of the sliding sets; nodes of fixed sets are skipped (u = 0
/// already satisfies it and CalculiX refuses a DOF both fixed and dependent).
void write_sliding(std::ostream& out, const Model& model, const Names& names, std::vector<std::string>& notes) {
  std::set<int> fixed;
  for (const NodeSet& s : model.node_sets)
    if (s.constraint == Constraint::Fixed) fixed.insert(s.nodes.begin(), s.nodes.end());
  std::map<int, std::vector<Eigen::Vector3d>> done;  // node -> normals already constrained
  std::map<int, std::array<bool, 3>> dependent;      // node -> dofs already dependent
  bool header = false;
  for (std::size_t k = 0; k < model.node_sets.size(); ++k) {
    const NodeSet& s = model.node_sets[k];
    if (s.constraint != Constraint::Sliding) continue;
    std::size_t skipped_fixed = 0, skipped_other = 0;
    for (std::size_t i = 0; i < s.nodes.size(); ++i) {
      const int v = s.nodes[i];
      const Eigen::Vector3d& n = s.normals[i];
      if (fixed.count(v)) {
        ++skipped_fixed;
        continue;
      }
      bool parallel = false;
      for (const Eigen::Vector3d& m : done[v]) parallel = parallel || std::abs(m.dot(n)) > 1.0 - 1e-9;
      // Dependent term: the largest |n_i| whose DOF is not already dependent in this node.
      std::array<int, 3> order{0, 1, 2};
      std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return std::abs(n[a]) > std::abs(n[b]); });
      auto& dep = dependent[v];
      int first = -1;
      for (int d : order)
        if (!dep[d] && std::abs(n[d]) >= 1e-12) {
          first = d;
          break;
        }
      if (parallel || first < 0) {
        ++skipped_other;
        continue;
      }
      dep[first] = true;
      done[v].push_back(n);
      if (!header) out << "** sliding: n . u = 0 per node, the dependent DOF first\n*EQUATION\n";
      header = true;
      int terms = 0;
      for (int d = 0; d < 3; ++d) terms += std::abs(n[d]) >= 1e-12;
      out << terms << "\n" << v + 1 << ", " << first + 1 << ", " << real(n[first]);
      for (int d = 0; d < 3; ++d)
        if (d != first && std::abs(n[d]) >= 1e-12) out << ", " << v + 1 << ", " << d + 1 << ", " << real(n[d]);
      out << "\n";
    }
    if (skipped_fixed)
      notes.push_back("sliding set " + names.node_set[k] + ": " + std::to_string(skipped_fixed) +
                      " node(s) also in a fixed set stay fixed (no *EQUATION)");
    if (skipped_other)
      notes.push_back("sliding set " + names.node_set[k] + ": " + std::to_string(skipped_other) +
                      " node(s) already constrained along the same normal by another sliding set");
  }
}

}  // namespace

std::string abaqus_name(const std::string& name) {
  std::string s = name;
  for (char& c : s) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return s;
}

std::vector<std::string> write_abaqus(const Model& model, std::ostream& out, const AbaqusOptions& options) {
  // Every refusal happens before the first byte is written.
  validate_model(model);
  check_materials(model);
  if (model.analysis.load_steps < 1 || model.analysis.max_load_steps < model.analysis.load_steps)
    throw InputError("abaqus: analysis needs load_steps >= 1 and max_load_steps >= load_steps");
  const Names names = check_names(model);
  std::vector<std::string> notes;
  const UnitSystem u = model.units;
  const bool linear = model.order == ElementOrder::Linear;
  const int npe = model.nodes_per_element();
  const std::string type = std::string(linear ? "C3D4" : "C3D10") + (options.hybrid ? "H" : "");
  if (options.hybrid)
    notes.push_back(type + " (hybrid) runs in Abaqus/Standard only: CalculiX rejects it as an unknown element type");

  // Elements per tissue in model order; tissues without elements are left out (an empty ELSET
  // would make *SOLID SECTION fail).
  std::vector<std::vector<int>> by_tissue(model.tissue_names.size());
  for (std::size_t e = 0; e < model.elements.size(); ++e) by_tissue[model.tissue_ids[e] - 1].push_back(static_cast<int>(e));
  std::vector<std::size_t> tissues;
  for (std::size_t t = 0; t < by_tissue.size(); ++t) {
    if (by_tissue[t].empty())
      notes.push_back("tissue " + names.tissue[t] + " has no elements: no element set, material or section written");
    else
      tissues.push_back(t);
  }
  if (linear)
    for (std::size_t t : tissues) {
      const MaterialSpec& m = model.materials[t];
      if (m.K_Pa / m.mu_Pa > 100.0) {
        notes.push_back("C3D4 locks with nearly incompressible tissue (" + names.tissue[t] + ": K/mu = " +
                        real(std::round(m.K_Pa / m.mu_Pa)) + "); tet10 recommended");
        break;
      }
    }

  // Heading: title, units, where each tissue's material comes from.
  out << "*HEADING\n" << one_line(model.title.empty() ? "tissuemesh model" : model.title) << " [units "
      << unit_system_name(u) << ": length " << length_unit(u) << ", stress " << stress_unit(u) << ", density "
      << density_unit(u) << ", acceleration " << acceleration_unit(u) << "]\n";
  out << "** written by tissuemesh: flat Abaqus/CalculiX deck, ids 1-based (element id = model element + 1)\n";
  for (std::size_t t = 0; t < model.tissue_names.size(); ++t) {
    const MaterialSpec& m = model.materials[t];
    out << "** tissue " << names.tissue[t] << ": " << material_law_name(m.law)
        << ", source: " << one_line(m.source.empty() ? "(not given)" : m.source) << "\n";
  }

  out << "*NODE, NSET=NALL\n";
  for (std::size_t i = 0; i < model.nodes.size(); ++i) {
    const Eigen::Vector3d& p = model.nodes[i];
    out << i + 1 << ", " << real(length_from_mm(u, p.x())) << ", " << real(length_from_mm(u, p.y())) << ", "
        << real(length_from_mm(u, p.z())) << "\n";
  }
  for (std::size_t t : tissues) {
    out << "*ELEMENT, TYPE=" << type << ", ELSET=" << names.tissue[t] << "\n";
    for (int e : by_tissue[t]) {
      out << e + 1;  // 11 entries at most (C3D10): one line
      for (int k = 0; k < npe; ++k) out << ", " << model.elements[e][k] + 1;
      out << "\n";
    }
  }
  out << "*ELSET, ELSET=EALL\n";
  std::vector<std::string> sets;
  for (std::size_t t : tissues) sets.push_back(names.tissue[t]);
  write_list(out, sets);
  for (std::size_t k = 0; k < model.node_sets.size(); ++k) {
    const NodeSet& s = model.node_sets[k];
    out << "** node set " << s.name << " ("
        << (s.constraint == Constraint::Fixed ? "fixed" : "sliding") << "): " << one_line(s.selection) << "\n";
    out << "*NSET, NSET=" << names.node_set[k] << "\n";
    write_ids(out, s.nodes);
  }
  for (std::size_t k = 0; k < model.face_sets.size(); ++k) {
    const FaceSet& s = model.face_sets[k];
    std::array<std::vector<int>, 4> by_face;
    for (const auto& f : s.faces) by_face[f[1]].push_back(f[0]);
    out << "** face set " << s.name << ": " << one_line(s.selection) << "\n";
    for (int f = 0; f < 4; ++f) {
      if (by_face[f].empty()) continue;
      std::sort(by_face[f].begin(), by_face[f].end());
      by_face[f].erase(std::unique(by_face[f].begin(), by_face[f].end()), by_face[f].end());
      out << "*ELSET, ELSET=" << names.face_set[k] << "_S" << f + 1 << "\n";
      write_ids(out, by_face[f]);
    }
    out << "*SURFACE, NAME=" << names.face_set[k] << ", TYPE=ELEMENT\n";
    for (int f = 0; f < 4; ++f)
      if (!by_face[f].empty()) out << names.face_set[k] << "_S" << f + 1 << ", S" << f + 1 << "\n";
  }

  for (std::size_t t : tissues) write_material(out, names.tissue[t], model.materials[t], u, notes);
  for (std::size_t t : tissues)
    out << "*SOLID SECTION, ELSET=" << names.tissue[t] << ", MATERIAL=M_" << names.tissue[t] << "\n";

  std::vector<std::size_t> fixed_sets;
  for (std::size_t k = 0; k < model.node_sets.size(); ++k)
    if (model.node_sets[k].constraint == Constraint::Fixed) fixed_sets.push_back(k);
  if (!fixed_sets.empty()) {
    out << "*BOUNDARY\n";
    for (std::size_t k : fixed_sets) out << names.node_set[k] << ", 1, 3\n";
  }
  write_sliding(out, model, names, notes);
  if (fixed_sets.empty())
    notes.push_back("no fixed node set: the model is held only by sliding constraints and may move as a rigid body");

  const AnalysisSettings& a = model.analysis;
  const double step = 1.0 / a.load_steps;
  out << "*STEP, NLGEOM, INC=" << a.max_load_steps << "\n*STATIC\n"
      << real(step) << ", 1, " << real(a.min_step_fraction) << ", " << real(step) << "\n";
  const Eigen::Vector3d& g = model.gravity.acceleration_m_s2;
  if (g.norm() > 0.0) {
    const Eigen::Vector3d dir = g / g.norm();
    out << "** gravity " << one_line(model.gravity.name) << ": " << real(g.norm()) << " m/s^2\n*DLOAD\nEALL, GRAV, "
        << real(acceleration_from_m_per_s2(u, g.norm())) << ", " << real(dir.x()) << ", " << real(dir.y()) << ", "
        << real(dir.z()) << "\n";
  } else {
    notes.push_back("gravity is zero: the step has no load");
  }
  out << "*NODE PRINT, NSET=NALL\nU\n";
  for (std::size_t k : fixed_sets) out << "*NODE PRINT, NSET=" << names.node_set[k] << ", TOTALS=YES\nRF\n";
  out << "*NODE FILE\nU\n*EL FILE\nS, E\n*END STEP\n";
  return notes;
}

}  // namespace tissuemesh
