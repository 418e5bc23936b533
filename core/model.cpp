#include "core/model.h"

#include "core/errors.h"
#include "core/tet_mesh.h"

#include <Eigen/Geometry>

#include <cmath>
#include <regex>
#include <set>

namespace tissuemesh {

const std::array<int, 3>& face_corners(int f) {
  // Abaqus S1..S4 = (1,2,3) (1,4,2) (2,4,3) (3,4,1): on a positively oriented tet their
  // right-hand normals point inwards, so each is listed reversed here (outward).
  static const std::array<std::array<int, 3>, 4> kFaces{{{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {2, 0, 3}}};
  return kFaces.at(static_cast<std::size_t>(f));
}

const std::array<int, 3>& face_midsides(int f) {
  // Midside slot of edge (a,b): (0,1)->4 (1,2)->5 (2,0)->6 (0,3)->7 (1,3)->8 (2,3)->9; listed
  // for the edges (c0,c1) (c1,c2) (c2,c0) of face_corners(f).
  static const std::array<std::array<int, 3>, 4> kMid{{{6, 5, 4}, {4, 8, 7}, {5, 9, 8}, {6, 7, 9}}};
  return kMid.at(static_cast<std::size_t>(f));
}

double element_volume(const Model& model, std::size_t e) {
  const auto& el = model.elements[e];
  return signed_tet_volume(model.nodes[el[0]], model.nodes[el[1]], model.nodes[el[2]], model.nodes[el[3]]);
}

namespace {

void check_material(const MaterialSpec& m, const std::string& tissue) {
  const std::string who = "tissue '" + tissue + "' (" + material_law_name(m.law) + ")";
  auto positive = [&](double v, const char* what) {
    if (!(std::isfinite(v) && v > 0.0))
      throw InputError("model: " + who + ": " + what + " must be > 0, got " + std::to_string(v));
  };
  positive(m.mu_Pa, "shear modulus mu");
  positive(m.K_Pa, "bulk modulus K");
  positive(m.density_kg_m3, "density");
  if (m.law == MaterialLaw::Ogden && (m.ogden.empty() || m.ogden.size() > 3))
    throw InputError("model: " + who + ": Ogden needs 1 to 3 terms, got " + std::to_string(m.ogden.size()));
  // mu is stored next to the native parameters; writers use the native ones, so they must agree.
  double mu_native = m.mu_Pa;
  if (m.law == MaterialLaw::NeoHookean) mu_native = 2.0 * m.C10_Pa;
  if (m.law == MaterialLaw::MooneyRivlin) mu_native = 2.0 * (m.C10_Pa + m.C01_Pa);
  if (m.law == MaterialLaw::Ogden) {
    mu_native = 0.0;
    for (const OgdenTerm& t : m.ogden) mu_native += t.mu_Pa;
  }
  if (std::abs(mu_native - m.mu_Pa) > 1e-12 * m.mu_Pa)
    throw InputError("model: " + who + ": shear modulus " + std::to_string(m.mu_Pa) +
                     " Pa disagrees with the law's own parameters (" + std::to_string(mu_native) + " Pa)");
}

void check_name(const std::string& name, const std::string& kind) {
  static const std::regex kIdentifier("[A-Za-z_][A-Za-z0-9_]*");
  if (!std::regex_match(name, kIdentifier))
    throw InputError("model: " + kind + " name '" + name +
                     "' is not an identifier (letters, digits, '_', not starting with a digit): "
                     "every export format must be able to name it");
}

}  // namespace

void validate_model(const Model& model) {
  const std::size_t n_nodes = model.nodes.size();
  const std::size_t n_el = model.elements.size();
  const int npe = model.nodes_per_element();
  if (n_el == 0) throw InputError("model: has no elements");
  if (model.tissue_ids.size() != n_el)
    throw InputError("model: " + std::to_string(model.tissue_ids.size()) + " tissue ids for " +
                     std::to_string(n_el) + " elements");
  if (model.materials.size() != model.tissue_names.size())
    throw InputError("model: " + std::to_string(model.materials.size()) + " materials for " +
                     std::to_string(model.tissue_names.size()) + " tissues");
  if (model.num_corner_nodes < 0 || static_cast<std::size_t>(model.num_corner_nodes) > n_nodes)
    throw InputError("model: corner node count out of range");
  if (model.order == ElementOrder::Linear && static_cast<std::size_t>(model.num_corner_nodes) != n_nodes)
    throw InputError("model: a tet4 model must not have midside nodes");
  for (std::size_t i = 0; i < n_nodes; ++i)
    if (!model.nodes[i].allFinite())
      throw InputError("model: node " + std::to_string(i + 1) + " has a non-finite coordinate");
  for (std::size_t t = 0; t < model.tissue_names.size(); ++t) {
    check_name(model.tissue_names[t], "tissue");
    check_material(model.materials[t], model.tissue_names[t]);
  }
  std::vector<char> used(n_nodes, 0);
  for (std::size_t e = 0; e < n_el; ++e) {
    const int tid = model.tissue_ids[e];
    const std::string el = "element " + std::to_string(e + 1);
    if (tid < 1 || static_cast<std::size_t>(tid) > model.tissue_names.size())
      throw InputError("model: " + el + " has unknown tissue id " + std::to_string(tid) + " (tissues 1.." +
                       std::to_string(model.tissue_names.size()) + ")");
    for (int k = 0; k < npe; ++k) {
      const int v = model.elements[e][k];
      if (v < 0 || static_cast<std::size_t>(v) >= n_nodes)
        throw InputError("model: " + el + " (" + model.tissue_names[tid - 1] + ") node " + std::to_string(k + 1) +
                         " index " + std::to_string(v) + " is out of range");
      if (k < 4 && v >= model.num_corner_nodes)
        throw InputError("model: " + el + " corner " + std::to_string(k + 1) + " is a midside node");
      used[v] = 1;
    }
    if (!(element_volume(model, e) > 0.0))
      throw InputError("model: " + el + " (" + model.tissue_names[tid - 1] +
                       ") is inverted or flat (signed volume " + std::to_string(element_volume(model, e)) +
                       " mm^3)");
  }
  for (std::size_t i = 0; i < n_nodes; ++i)
    if (!used[i]) throw InputError("model: node " + std::to_string(i + 1) + " is used by no element (orphan)");
  std::set<std::string> names;
  for (const NodeSet& s : model.node_sets) {
    check_name(s.name, "node set");
    if (!names.insert(s.name).second) throw InputError("model: set name '" + s.name + "' is used twice");
    if (s.nodes.empty()) throw InputError("model: node set '" + s.name + "' (" + s.selection + ") is empty");
    for (std::size_t i = 0; i < s.nodes.size(); ++i) {
      if (s.nodes[i] < 0 || static_cast<std::size_t>(s.nodes[i]) >= n_nodes)
        throw InputError("model: node set '" + s.name + "' has an out-of-range node");
      if (i > 0 && s.nodes[i] <= s.nodes[i - 1])
        throw InputError("model: node set '" + s.name + "' is not sorted and unique");
    }
    if (s.constraint == Constraint::Sliding) {
      if (s.normals.size() != s.nodes.size())
        throw InputError("model: sliding node set '" + s.name + "' needs one normal per node");
      for (const Eigen::Vector3d& n : s.normals)
        if (!n.allFinite() || std::abs(n.norm() - 1.0) > 1e-9)
          throw InputError("model: sliding node set '" + s.name + "' has a normal that is not a unit vector");
    }
  }
  for (const FaceSet& s : model.face_sets) {
    check_name(s.name, "face set");
    if (!names.insert(s.name).second) throw InputError("model: set name '" + s.name + "' is used twice");
    if (s.faces.empty()) throw InputError("model: face set '" + s.name + "' (" + s.selection + ") is empty");
    for (const auto& f : s.faces)
      if (f[0] < 0 || static_cast<std::size_t>(f[0]) >= n_el || f[1] < 0 || f[1] > 3)
        throw InputError("model: face set '" + s.name + "' has an invalid (element, face) pair");
  }
  if (!model.gravity.acceleration_m_s2.allFinite())
    throw InputError("model: gravity is not finite");
}

}  // namespace tissuemesh
