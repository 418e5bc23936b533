#include "core/model_builder.h"

#include "core/errors.h"
#include "core/node_ordering.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <map>
#include <set>
#include <tuple>
#include <unordered_map>

namespace tissuemesh {

namespace {

// Corner pairs of the six tet10 edges in midside slot order 4..9 (core/model.h).
constexpr int kEdges[6][2] = {{0, 1}, {1, 2}, {2, 0}, {0, 3}, {1, 3}, {2, 3}};

std::uint64_t edge_key(int a, int b) {
  if (a > b) std::swap(a, b);
  return (static_cast<std::uint64_t>(a) << 32) | static_cast<std::uint32_t>(b);
}

// Sorted corner triple of a face: the key under which the two elements sharing it meet.
std::array<int, 3> face_key(const Model& m, std::size_t e, int f) {
  std::array<int, 3> k;
  for (int i = 0; i < 3; ++i) k[i] = m.elements[e][face_corners(f)[i]];
  std::sort(k.begin(), k.end());
  return k;
}

// Tissue id -> side membership (index 0 = outside).
std::vector<char> side_mask(const Model& m, const InterfaceSide& side, const std::string& set_name) {
  std::vector<char> mask(m.tissue_names.size() + 1, 0);
  mask[0] = side.outside ? 1 : 0;
  for (const std::string& name : side.tissues) {
    auto it = std::find(m.tissue_names.begin(), m.tissue_names.end(), name);
    if (it == m.tissue_names.end()) {
      std::string known;
      for (const std::string& t : m.tissue_names) known += (known.empty() ? "" : ", ") + t;
      throw InputError("model: set '" + set_name + "': unknown tissue '" + name + "' (the mesh has " + known +
                       ", and 'outside')");
    }
    mask[static_cast<std::size_t>(it - m.tissue_names.begin()) + 1] = 1;
  }
  return mask;
}

/// Per element face (index 4 e + f): the (element, face) across it, or {-1, -1} on the boundary.
using FaceNeighbours = std::vector<std::array<int, 2>>;

FaceNeighbours face_neighbours(const Model& m) {
  // Faces bucketed by their lowest corner (counting sort), each bucket sorted by the other two
  // corners, then by position, so equal keys are adjacent. In a conforming mesh a key occurs at
  // most twice; otherwise every later face gets the first as neighbour and the first the last.
  const std::size_t faces = m.elements.size() * 4;
  std::vector<std::array<int, 3>> key(faces);
  std::vector<int> bucket_start(m.nodes.size() + 1, 0);
  for (std::size_t e = 0; e < m.elements.size(); ++e)
    for (int f = 0; f < 4; ++f) {
      key[e * 4 + static_cast<std::size_t>(f)] = face_key(m, e, f);
      ++bucket_start[key[e * 4 + static_cast<std::size_t>(f)][0] + 1];
    }
  for (std::size_t v = 0; v < m.nodes.size(); ++v) bucket_start[v + 1] += bucket_start[v];
  std::vector<std::size_t> sorted(faces);
  {
    std::vector<int> fill(bucket_start.begin(), bucket_start.end() - 1);
    for (std::size_t slot = 0; slot < faces; ++slot) sorted[fill[key[slot][0]]++] = slot;  // by position within a bucket
  }
  auto face_of = [](std::size_t slot) { return std::array<int, 2>{static_cast<int>(slot / 4), static_cast<int>(slot % 4)}; };
  FaceNeighbours neighbour(faces, {-1, -1});
  for (std::size_t v = 0; v < m.nodes.size(); ++v) {
    const auto begin = sorted.begin() + bucket_start[v], end = sorted.begin() + bucket_start[v + 1];
    std::sort(begin, end, [&](std::size_t x, std::size_t y) { return std::tie(key[x], x) < std::tie(key[y], y); });
    for (auto i = begin; i != end;) {
      auto j = i + 1;
      for (; j != end && key[*j] == key[*i]; ++j) {
        neighbour[*j] = face_of(*i);
        neighbour[*i] = face_of(*j);
      }
      i = j;
    }
  }
  return neighbour;
}

std::vector<std::array<int, 2>> faces_between(const Model& m, const FaceNeighbours& neighbour, const InterfaceSide& a,
                                              const InterfaceSide& b, const std::string& set_name) {
  const std::vector<char> in_a = side_mask(m, a, set_name), in_b = side_mask(m, b, set_name);
  // Keep the face on side A's element so that its outward normal points from A to B.
  std::vector<std::array<int, 2>> out;
  for (std::size_t e = 0; e < m.elements.size(); ++e) {
    if (!in_a[m.tissue_ids[e]]) continue;
    for (int f = 0; f < 4; ++f) {
      const auto& nb = neighbour[e * 4 + f];
      const int other = nb[0] < 0 ? 0 : m.tissue_ids[nb[0]];
      if (other == m.tissue_ids[e] && nb[0] >= 0) continue;  // inside one tissue: no interface
      if (in_b[other]) out.push_back({static_cast<int>(e), f});
    }
  }
  return out;
}

Eigen::Vector3d face_area_normal(const Model& m, const std::array<int, 2>& face) {
  const auto& c = face_corners(face[1]);
  const auto& el = m.elements[face[0]];
  const Eigen::Vector3d &p0 = m.nodes[el[c[0]]], &p1 = m.nodes[el[c[1]]], &p2 = m.nodes[el[c[2]]];
  return 0.5 * (p1 - p0).cross(p2 - p0);
}

std::vector<std::array<int, 2>> select_faces(const Model& m, const FaceNeighbours& neighbour, const SetSelection& s,
                                             const std::string& name) {
  if (s.kind == SetSelection::Kind::Between) return faces_between(m, neighbour, s.side_a, s.side_b, name);
  // Plane / box: boundary faces whose corners all lie in the selection.
  InterfaceSide all, outside;
  all.tissues = m.tissue_names;
  outside.outside = true;
  std::vector<std::array<int, 2>> out;
  for (const auto& face : faces_between(m, neighbour, all, outside, name)) {
    bool inside = true;
    for (int c : face_corners(face[1])) {
      const Eigen::Vector3d& p = m.nodes[m.elements[face[0]][c]];
      if (s.kind == SetSelection::Kind::Plane)
        inside = inside && std::abs((p - s.plane_point_mm).dot(s.plane_normal)) <= s.plane_tolerance_mm;
      else
        inside = inside && (p.array() >= s.box_min_mm.array()).all() && (p.array() <= s.box_max_mm.array()).all();
    }
    if (inside) out.push_back(face);
  }
  return out;
}

std::vector<int> select_corner_nodes(const Model& m, const SetSelection& s,
                                     const std::vector<std::array<int, 2>>& faces) {
  std::set<int> nodes;
  if (s.kind == SetSelection::Kind::Between) {
    for (const auto& f : faces)
      for (int c : face_corners(f[1])) nodes.insert(m.elements[f[0]][c]);
  } else {
    for (int i = 0; i < m.num_corner_nodes; ++i) {
      const Eigen::Vector3d& p = m.nodes[i];
      const bool in = s.kind == SetSelection::Kind::Plane
                          ? std::abs((p - s.plane_point_mm).dot(s.plane_normal)) <= s.plane_tolerance_mm
                          : (p.array() >= s.box_min_mm.array()).all() && (p.array() <= s.box_max_mm.array()).all();
      if (in) nodes.insert(i);
    }
  }
  return {nodes.begin(), nodes.end()};
}

// `faces` receives the triangles a `between` selection found (the tet10 step needs them).
NodeSet make_node_set(const Model& m, const FaceNeighbours& neighbour, const NodeSetSettings& settings,
                      std::vector<std::array<int, 2>>& faces) {
  NodeSet set;
  set.name = settings.name;
  set.constraint = settings.constraint;
  set.selection = settings.selection.describe();
  faces = select_faces(m, neighbour, settings.selection, settings.name);
  set.nodes = select_corner_nodes(m, settings.selection, faces);
  if (set.nodes.empty())
    throw InputError("model: node set '" + set.name + "' (" + set.selection + ") selects no node");
  if (set.constraint == Constraint::Sliding) {
    if (settings.selection.kind == SetSelection::Kind::Box)
      throw InputError("model: node set '" + set.name + "': a box selection cannot slide (no surface normal); "
                       "use `between` or `plane`");
    std::unordered_map<int, Eigen::Vector3d> sum;
    if (settings.selection.kind == SetSelection::Kind::Plane) {
      for (int v : set.nodes) sum[v] = settings.selection.plane_normal;
    } else {
      for (const auto& f : faces)
        for (int c : face_corners(f[1])) {
          auto [it, ok] = sum.emplace(m.elements[f[0]][c], Eigen::Vector3d::Zero());
          it->second += face_area_normal(m, f);
        }
    }
    for (int v : set.nodes) set.normals.push_back(sum.at(v).normalized());
  }
  return set;
}

// tet10: the midside nodes that join a node set. For an interface (`between`) set, those of its
// triangles: an edge joining two interface nodes may cut through the tissue, and its midside node
// must then stay free. For plane and box sets, every edge with both ends in the set. A sliding
// node's normal is the mean of its edge ends'.
void extend_to_midsides(const Model& m, NodeSet& set, const std::vector<std::array<int, 2>>* faces) {
  std::unordered_map<int, std::size_t> pos;
  for (std::size_t i = 0; i < set.nodes.size(); ++i) pos[set.nodes[i]] = i;
  std::map<int, Eigen::Vector3d> added;
  auto add = [&](const std::array<int, 10>& el, int k) {
    auto a = pos.find(el[kEdges[k][0]]), b = pos.find(el[kEdges[k][1]]);
    if (a == pos.end() || b == pos.end()) return;
    Eigen::Vector3d n = Eigen::Vector3d::Zero();
    if (set.constraint == Constraint::Sliding) n = (set.normals[a->second] + set.normals[b->second]).normalized();
    added.emplace(el[4 + k], n);
  };
  if (faces) {
    for (const auto& f : *faces)
      for (int slot : face_midsides(f[1])) add(m.elements[f[0]], slot - 4);
  } else {
    for (const auto& el : m.elements)
      for (int k = 0; k < 6; ++k) add(el, k);
  }
  for (const auto& [v, n] : added) {
    set.nodes.push_back(v);
    if (set.constraint == Constraint::Sliding) set.normals.push_back(n);
  }
  // Keep nodes sorted (midside indices are all larger than corner indices, and `added` is sorted).
}

// A node both fixed and sliding is fixed: writing both would over-constrain it (CalculiX refuses
// an *EQUATION on a node whose degrees of freedom are all fixed).
void drop_fixed_from_sliding(Model& m) {
  std::set<int> fixed;
  for (const NodeSet& s : m.node_sets)
    if (s.constraint == Constraint::Fixed) fixed.insert(s.nodes.begin(), s.nodes.end());
  for (NodeSet& s : m.node_sets) {
    if (s.constraint != Constraint::Sliding) continue;
    NodeSet kept = s;
    kept.nodes.clear();
    kept.normals.clear();
    for (std::size_t i = 0; i < s.nodes.size(); ++i)
      if (!fixed.count(s.nodes[i])) {
        kept.nodes.push_back(s.nodes[i]);
        kept.normals.push_back(s.normals[i]);
      }
    if (kept.nodes.empty())
      throw InputError("model: sliding node set '" + s.name + "' (" + s.selection + ") lies entirely on fixed nodes");
    s = std::move(kept);
  }
}

// Renumbers the nodes by reverse Cuthill-McKee while keeping the corners first (core/model.h):
// corners by RCM on the corner graph, then midside nodes by (lower, higher) new index of their
// edge's ends. Elements, node sets (re-sorted, normals kept paired) and mesh_node_of follow; face
// sets are (element, face) pairs and elements keep their order.
void renumber_nodes_rcm(Model& m) {
  const int corners = m.num_corner_nodes;
  std::vector<int> new_of_old = reverse_cuthill_mckee(corners, m.elements, 4);
  new_of_old.resize(m.nodes.size(), -1);
  if (m.order == ElementOrder::Quadratic) {
    std::vector<std::array<int, 3>> midsides;  // (lower new end, higher new end, old index)
    midsides.reserve(m.nodes.size() - static_cast<std::size_t>(corners));
    std::vector<char> seen(m.nodes.size(), 0);
    for (const auto& el : m.elements)
      for (int k = 0; k < 6; ++k) {
        const int v = el[4 + k];
        if (seen[v]) continue;
        seen[v] = 1;
        const int a = new_of_old[el[kEdges[k][0]]], b = new_of_old[el[kEdges[k][1]]];
        midsides.push_back({std::min(a, b), std::max(a, b), v});
      }
    std::sort(midsides.begin(), midsides.end());
    for (std::size_t i = 0; i < midsides.size(); ++i) new_of_old[midsides[i][2]] = corners + static_cast<int>(i);
  }
  std::vector<Eigen::Vector3d> nodes(m.nodes.size());
  for (std::size_t i = 0; i < m.nodes.size(); ++i) nodes[new_of_old[i]] = m.nodes[i];
  m.nodes = std::move(nodes);
  std::vector<int> mesh_node_of(static_cast<std::size_t>(corners));
  for (int i = 0; i < corners; ++i) mesh_node_of[new_of_old[i]] = m.mesh_node_of[i];
  m.mesh_node_of = std::move(mesh_node_of);
  const int npe = m.nodes_per_element();
  for (auto& el : m.elements)
    for (int k = 0; k < npe; ++k) el[k] = new_of_old[el[k]];
  for (NodeSet& s : m.node_sets) {
    std::vector<std::size_t> at(s.nodes.size());
    for (std::size_t i = 0; i < at.size(); ++i) {
      at[i] = i;
      s.nodes[i] = new_of_old[s.nodes[i]];
    }
    std::sort(at.begin(), at.end(), [&](std::size_t x, std::size_t y) { return s.nodes[x] < s.nodes[y]; });
    NodeSet sorted = s;
    for (std::size_t i = 0; i < at.size(); ++i) {
      sorted.nodes[i] = s.nodes[at[i]];
      if (!s.normals.empty()) sorted.normals[i] = s.normals[at[i]];
    }
    s = std::move(sorted);
  }
}

// With the RCM numbering: elements within a tissue ordered by their lowest corner (ties keep their
// order), so that consecutive elements share nodes and nearby nodes get nearby ids. Face sets
// follow. The built-in solver's assembly is then faster: its matrix writes and displacement reads
// stay close together instead of jumping across the arrays as with the mesher's cell order.
void order_elements_by_lowest_node(Model& m) {
  const std::size_t n = m.elements.size();
  std::vector<int> order(n), lowest(n);
  for (std::size_t e = 0; e < n; ++e) {
    order[e] = static_cast<int>(e);
    lowest[e] = *std::min_element(m.elements[e].begin(), m.elements[e].begin() + 4);
  }
  std::stable_sort(order.begin(), order.end(), [&](int x, int y) {
    return m.tissue_ids[x] != m.tissue_ids[y] ? m.tissue_ids[x] < m.tissue_ids[y] : lowest[x] < lowest[y];
  });
  std::vector<std::array<int, 10>> elements(n);
  std::vector<int> tissue_ids(n), new_of_old(n);
  for (std::size_t k = 0; k < n; ++k) {
    elements[k] = m.elements[order[k]];
    tissue_ids[k] = m.tissue_ids[order[k]];
    new_of_old[order[k]] = static_cast<int>(k);
  }
  m.elements = std::move(elements);
  m.tissue_ids = std::move(tissue_ids);
  for (FaceSet& set : m.face_sets)
    for (auto& face : set.faces) face[0] = new_of_old[face[0]];
}

}  // namespace

void make_quadratic(Model& model) {
  if (model.order == ElementOrder::Quadratic) return;
  std::unordered_map<std::uint64_t, int> midside;
  for (auto& el : model.elements)
    for (int k = 0; k < 6; ++k) {
      const int a = el[kEdges[k][0]], b = el[kEdges[k][1]];
      auto [it, inserted] = midside.emplace(edge_key(a, b), static_cast<int>(model.nodes.size()));
      if (inserted) model.nodes.push_back(0.5 * (model.nodes[a] + model.nodes[b]));
      el[4 + k] = it->second;
    }
  model.order = ElementOrder::Quadratic;
}

std::vector<std::array<int, 2>> interface_faces(const Model& model, const InterfaceSide& a, const InterfaceSide& b) {
  return faces_between(model, face_neighbours(model), a, b, "<interface>");
}

Model build_model(const TetMesh& mesh, const ModelSettings& settings,
                  const std::map<std::string, MaterialSpec>& materials, const std::string& materials_source) {
  mesh.validate("mesh");
  Model m;
  m.nodes = mesh.points;
  m.num_corner_nodes = static_cast<int>(mesh.points.size());
  m.mesh_node_of.resize(mesh.points.size());
  for (std::size_t i = 0; i < mesh.points.size(); ++i) m.mesh_node_of[i] = static_cast<int>(i);
  // Elements grouped by tissue (stable within a tissue; by lowest node at the end with `rcm`): every
  // format then numbers them the same way (FEBio needs one contiguous block per tissue,
  // Abaqus/CalculiX ids follow the model).
  std::vector<std::size_t> order(mesh.tets.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return mesh.tissue_ids[a] < mesh.tissue_ids[b]; });
  m.elements.reserve(mesh.tets.size());
  for (std::size_t i : order) {
    std::array<int, 10> el;
    el.fill(-1);
    std::copy(mesh.tets[i].begin(), mesh.tets[i].end(), el.begin());
    m.elements.push_back(el);
    m.tissue_ids.push_back(mesh.tissue_ids[i]);
  }
  m.tissue_names = mesh.tissue_names;
  for (const std::string& name : m.tissue_names) {
    auto it = materials.find(name);
    if (it == materials.end())
      throw InputError(materials_source + ": materials: tissue '" + name +
                       "' of the mesh has no material (add `materials: " + name + ": {...}`)");
    m.materials.push_back(it->second);
  }
  // One neighbour table for every set: sorting the faces is most of a selection's time.
  const bool any_set = !settings.node_sets.empty() || !settings.face_sets.empty();
  const FaceNeighbours neighbours = any_set ? face_neighbours(m) : FaceNeighbours{};
  std::vector<std::vector<std::array<int, 2>>> set_faces(settings.node_sets.size());
  for (std::size_t i = 0; i < settings.node_sets.size(); ++i)
    m.node_sets.push_back(make_node_set(m, neighbours, settings.node_sets[i], set_faces[i]));
  for (const FaceSetSettings& s : settings.face_sets) {
    FaceSet set{s.name, select_faces(m, neighbours, s.selection, s.name), s.selection.describe()};
    if (set.faces.empty())
      throw InputError("model: face set '" + set.name + "' (" + set.selection + ") selects no face");
    m.face_sets.push_back(std::move(set));
  }
  m.gravity.acceleration_m_s2 = settings.gravity.acceleration();
  m.gravity.name = settings.gravity.direction;
  m.units = settings.units;
  m.analysis = settings.analysis;
  if (settings.element.value_or(default_element(m.materials)) == ElementOrder::Quadratic) {
    make_quadratic(m);
    for (std::size_t i = 0; i < m.node_sets.size(); ++i) {
      const bool interface = settings.node_sets[i].selection.kind == SetSelection::Kind::Between;
      extend_to_midsides(m, m.node_sets[i], interface ? &set_faces[i] : nullptr);
    }
  }
  drop_fixed_from_sliding(m);
  // After make_quadratic and the set extension, so that midside nodes are renumbered too.
  if (settings.node_order == NodeOrder::ReverseCuthillMcKee) {
    renumber_nodes_rcm(m);
    order_elements_by_lowest_node(m);
  }
  validate_model(m);
  return m;
}

}  // namespace tissuemesh
