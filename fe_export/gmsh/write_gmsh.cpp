// The model as a Gmsh .msh 4.1 (ASCII) through the Gmsh SDK.
//
// Entities: volume t+1 per tissue (its tets; every node is classified on the first volume, in
// tissue order, whose tets use it: Gmsh classifies each node on exactly one entity, and elements
// of other entities refer to it by tag), physical group dim 3 tag = tissue id; per node set one
// point entity per node (placed at the node) with a type-15 point element, all in one physical
// group of dim 0; per face set a discrete surface with its triangles and a physical group of
// dim 2. Element tags: tets e+1, then points, then triangles, so they are unique.
#include "fe_export/gmsh/write_gmsh.h"

#include "core/errors.h"
#include "fe_export/gmsh/gmsh_session.h"

#include <array>
#include <exception>

namespace tissuemesh {

namespace {

constexpr int kTet4 = 4, kTet10 = 11, kTri3 = 2, kTri6 = 9, kPoint = 15;  // Gmsh element types

// Gmsh's tet10 differs from VTK's/the Model's in the last two midside nodes: Gmsh slot 8 is edge
// (2,3), slot 9 edge (1,3) (Gmsh's getElementProperties(11) local coordinates).
constexpr std::array<int, 10> kModelSlotOfGmshTet10{0, 1, 2, 3, 4, 5, 6, 7, 9, 8};

void build(const Model& model) {
  const std::size_t n_nodes = model.nodes.size();
  const std::size_t n_tissues = model.tissue_names.size();
  const int npe = model.nodes_per_element();
  gmsh_sdk::add_model("tissuemesh");

  std::vector<std::vector<std::size_t>> tets_of(n_tissues);
  for (std::size_t e = 0; e < model.elements.size(); ++e)
    tets_of[static_cast<std::size_t>(model.tissue_ids[e] - 1)].push_back(e);
  std::vector<int> owner(n_nodes, -1);  // tissue index whose volume holds the node
  for (std::size_t t = 0; t < n_tissues; ++t)
    for (std::size_t e : tets_of[t])
      for (int k = 0; k < npe; ++k) {
        int& o = owner[static_cast<std::size_t>(model.elements[e][k])];
        if (o < 0) o = static_cast<int>(t);
      }

  // Volumes and their nodes first: elements may only refer to existing nodes.
  for (std::size_t t = 0; t < n_tissues; ++t) {
    if (tets_of[t].empty()) continue;
    const int tag = static_cast<int>(t + 1);
    gmsh_sdk::add_discrete_entity(3, tag);
    std::vector<std::size_t> node_tags;
    std::vector<double> coords;
    for (std::size_t i = 0; i < n_nodes; ++i)
      if (owner[i] == static_cast<int>(t)) {
        node_tags.push_back(i + 1);
        coords.insert(coords.end(), model.nodes[i].data(), model.nodes[i].data() + 3);
      }
    gmsh_sdk::add_nodes(3, tag, node_tags, coords);
  }
  for (std::size_t t = 0; t < n_tissues; ++t) {
    if (tets_of[t].empty()) continue;
    const int tag = static_cast<int>(t + 1);
    std::vector<std::size_t> element_tags, node_tags;
    for (std::size_t e : tets_of[t]) {
      element_tags.push_back(e + 1);
      for (int k = 0; k < npe; ++k) {
        const int slot = model.order == ElementOrder::Linear ? k : kModelSlotOfGmshTet10[static_cast<std::size_t>(k)];
        node_tags.push_back(static_cast<std::size_t>(model.elements[e][slot]) + 1);
      }
    }
    gmsh_sdk::add_elements_by_type(tag, model.order == ElementOrder::Linear ? kTet4 : kTet10, element_tags,
                                         node_tags);
    gmsh_sdk::add_physical_group(3, {tag}, tag);
    gmsh_sdk::set_physical_name(3, tag, model.tissue_names[t]);
  }

  std::size_t next_element = model.elements.size() + 1;
  int next_point = 1;
  for (std::size_t s = 0; s < model.node_sets.size(); ++s) {
    const NodeSet& set = model.node_sets[s];
    std::vector<int> points;
    for (int n : set.nodes) {
      const int p = gmsh_sdk::add_discrete_entity(0, next_point++);
      const Eigen::Vector3d& x = model.nodes[static_cast<std::size_t>(n)];
      gmsh_sdk::set_coordinates(p, x.x(), x.y(), x.z());
      gmsh_sdk::add_elements_by_type(p, kPoint, {next_element++}, {static_cast<std::size_t>(n) + 1});
      points.push_back(p);
    }
    const int group = static_cast<int>(s + 1);
    gmsh_sdk::add_physical_group(0, points, group);
    gmsh_sdk::set_physical_name(0, group, set.name);
  }

  for (std::size_t f = 0; f < model.face_sets.size(); ++f) {
    const FaceSet& set = model.face_sets[f];
    const int tag = static_cast<int>(f + 1);
    gmsh_sdk::add_discrete_entity(2, tag);
    std::vector<std::size_t> element_tags, node_tags;
    for (const auto& [e, face] : set.faces) {
      const auto& el = model.elements[static_cast<std::size_t>(e)];
      element_tags.push_back(next_element++);
      for (int c : face_corners(face)) node_tags.push_back(static_cast<std::size_t>(el[c]) + 1);
      if (model.order == ElementOrder::Quadratic)  // tri6: midsides of (c0,c1) (c1,c2) (c2,c0), Gmsh's order
        for (int m : face_midsides(face)) node_tags.push_back(static_cast<std::size_t>(el[m]) + 1);
    }
    gmsh_sdk::add_elements_by_type(tag, model.order == ElementOrder::Linear ? kTri3 : kTri6, element_tags,
                                         node_tags);
    gmsh_sdk::add_physical_group(2, {tag}, tag);
    gmsh_sdk::set_physical_name(2, tag, set.name);
  }
}

}  // namespace

void write_gmsh(const Model& model, const std::string& path) {
  validate_model(model);  // every writer refuses an invalid model first, also when called directly
  try {
    GmshSession session;
    build(model);
    gmsh_sdk::set_number("Mesh.MshFileVersion", 4.1);
    gmsh_sdk::set_number("Mesh.Binary", 0);
    gmsh_sdk::set_number("Mesh.SaveAll", 0);  // every entity has a physical group: all is saved
    gmsh_sdk::write(path);
  } catch (const Error&) {
    throw;
  } catch (const std::exception& e) {  // Gmsh's message, or why the SDK could not be loaded
    throw OutputError(path + ": cannot write Gmsh mesh: " + e.what());
  }
}

}  // namespace tissuemesh
