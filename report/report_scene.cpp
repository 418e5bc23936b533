#include "report/report_scene.h"

#include "core/errors.h"
#include "quality/mesh_interfaces.h"
#include "quality/mesh_quality.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <tuple>

namespace tissuemesh {

namespace {

std::size_t base64_bytes(std::size_t raw) { return 4 * ((raw + 2) / 3); }

std::size_t face_count(const ReportScene& s) {
  std::size_t n = s.outer_faces.size();
  for (const auto& f : s.tissue_faces) n += f.size();
  return n;
}

/// Renumbers the nodes so that only those a face, a tet or nothing else uses remain (in order).
void compact_nodes(ReportScene& s) {
  std::vector<int> new_id(s.nodes.size(), -1);
  auto mark = [&](int v) { new_id[static_cast<std::size_t>(v)] = 0; };
  for (const auto& faces : s.tissue_faces)
    for (const auto& f : faces) for (int v : f) mark(v);
  for (const auto& f : s.outer_faces) for (int v : f) mark(v);
  for (const auto& t : s.tets) for (int v : t) mark(v);
  std::vector<Eigen::Vector3d> nodes, disp;
  for (std::size_t i = 0; i < s.nodes.size(); ++i)
    if (new_id[i] == 0) {
      new_id[i] = static_cast<int>(nodes.size());
      nodes.push_back(s.nodes[i]);
      if (!s.displacement_mm.empty()) disp.push_back(s.displacement_mm[i]);
    }
  auto remap = [&](auto& cells) {
    for (auto& c : cells) for (int& v : c) v = new_id[static_cast<std::size_t>(v)];
  };
  for (auto& faces : s.tissue_faces) remap(faces);
  remap(s.outer_faces);
  remap(s.tets);
  s.nodes = std::move(nodes);
  if (!s.displacement_mm.empty()) s.displacement_mm = std::move(disp);
}

/// Vertex clustering (Rossignac & Borrel 1993): nodes in one grid cell of edge h become the
/// cell's first node; triangles that collapse are dropped, duplicates kept once.
void cluster_faces(ReportScene& s, double h) {
  Eigen::Vector3d lo = s.nodes.front();
  for (const auto& p : s.nodes) lo = lo.cwiseMin(p);
  std::map<std::array<long long, 3>, int> rep_of_cell;
  std::vector<int> rep(s.nodes.size());
  for (std::size_t i = 0; i < s.nodes.size(); ++i) {
    const Eigen::Vector3d c = (s.nodes[i] - lo) / h;
    const std::array<long long, 3> key{static_cast<long long>(std::floor(c.x())), static_cast<long long>(std::floor(c.y())),
                                       static_cast<long long>(std::floor(c.z()))};
    rep[i] = rep_of_cell.emplace(key, static_cast<int>(i)).first->second;
  }
  auto collapse = [&](std::vector<std::array<int, 3>>& faces) {
    std::vector<std::array<int, 3>> kept;
    std::set<std::array<int, 3>> seen;
    for (const auto& f : faces) {
      const std::array<int, 3> g{rep[static_cast<std::size_t>(f[0])], rep[static_cast<std::size_t>(f[1])],
                                 rep[static_cast<std::size_t>(f[2])]};
      if (g[0] == g[1] || g[1] == g[2] || g[0] == g[2]) continue;
      std::array<int, 3> key = g;
      std::rotate(key.begin(), std::min_element(key.begin(), key.end()), key.end());
      if (seen.insert(key).second) kept.push_back(g);
    }
    faces = std::move(kept);
  };
  for (auto& faces : s.tissue_faces) collapse(faces);
  collapse(s.outer_faces);
  compact_nodes(s);
}

}  // namespace

ReportScene scene_of_mesh(const TetMesh& mesh) {
  if (mesh.num_tissues() > 255) throw InputError("report.html: more than 255 tissues (" + std::to_string(mesh.num_tissues()) + ")");
  ReportScene s;
  s.nodes = mesh.points;
  s.tissue_names = mesh.tissue_names;
  s.mesh_tets = mesh.tets.size();
  std::vector<int> node_of_point;
  const TriSurface surface = interface_surface(mesh, &node_of_point);
  auto node = [&](int p) { return node_of_point[static_cast<std::size_t>(p)]; };
  s.tissue_faces.resize(mesh.num_tissues());
  for (std::size_t t = 0; t < surface.triangles.size(); ++t) {
    const auto& tri = surface.triangles[t];
    const auto [p, q] = surface.labels[t];
    // The normal points from p into q: outward for p, reversed for q.
    const std::array<int, 3> forward{node(tri[0]), node(tri[1]), node(tri[2])};
    const std::array<int, 3> reversed{forward[0], forward[2], forward[1]};
    if (p > 0) s.tissue_faces[static_cast<std::size_t>(p - 1)].push_back(forward);
    if (q > 0) s.tissue_faces[static_cast<std::size_t>(q - 1)].push_back(reversed);
    if (p == 0) s.outer_faces.push_back(reversed);
  }
  s.tets = mesh.tets;
  s.tet_tissue.reserve(mesh.tets.size());
  s.tet_min_dihedral_deg.reserve(mesh.tets.size());
  for (std::size_t t = 0; t < mesh.tets.size(); ++t) {
    const auto& c = mesh.tets[t];
    const TetVolumeAndAngle va = tet_volume_and_min_dihedral(mesh.points[static_cast<std::size_t>(c[0])], mesh.points[static_cast<std::size_t>(c[1])],
                                                              mesh.points[static_cast<std::size_t>(c[2])], mesh.points[static_cast<std::size_t>(c[3])]);
    s.tet_tissue.push_back(static_cast<unsigned char>(mesh.tissue_ids[t]));
    s.tet_min_dihedral_deg.push_back(static_cast<float>(va.min_dihedral_deg));
  }
  // The section starts through the tumour when there is one: what a user looks for first.
  if (const int tumour = tumour_tissue_id(mesh.tissue_names)) s.clip_at_mm = tissue_centroid(mesh, tumour, mesh.points);
  return s;
}

int tumour_tissue_id(const std::vector<std::string>& names) {
  for (std::size_t i = 0; i < names.size(); ++i)
    if (names[i] == "tumor" || names[i] == "tumour") return static_cast<int>(i + 1);
  return 0;
}

std::optional<Eigen::Vector3d> tissue_centroid(const TetMesh& mesh, int id, const std::vector<Eigen::Vector3d>& positions) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  double volume = 0;
  for (std::size_t t = 0; t < mesh.tets.size(); ++t) {
    if (mesh.tissue_ids[t] != id) continue;
    const auto& c = mesh.tets[t];
    const auto p = [&](int k) -> const Eigen::Vector3d& { return positions[static_cast<std::size_t>(c[k])]; };
    const double v = std::abs(signed_tet_volume(p(0), p(1), p(2), p(3)));
    sum += v * (p(0) + p(1) + p(2) + p(3)) / 4.0;
    volume += v;
  }
  if (volume <= 0) return std::nullopt;
  return sum / volume;
}


std::size_t scene_page_bytes(const ReportScene& s) {
  std::size_t bytes = base64_bytes(12 * s.nodes.size()) + base64_bytes(16 * s.tets.size()) +
                      base64_bytes(s.tet_tissue.size()) + base64_bytes(4 * s.tet_min_dihedral_deg.size()) +
                      base64_bytes(12 * s.displacement_mm.size()) + base64_bytes(24 * s.junction_segments.size()) +
                      base64_bytes(12 * s.outer_faces.size());
  for (const auto& f : s.tissue_faces) bytes += base64_bytes(12 * f.size());
  return bytes;
}

std::string fit_scene(ReportScene& s, std::size_t max_bytes) {
  if (scene_page_bytes(s) <= max_bytes || s.nodes.empty()) return {};
  // 1. Thin the section: keep one tet in k.
  const std::size_t tet_bytes = base64_bytes(21 * s.tets.size());
  const std::size_t other = scene_page_bytes(s) - std::min(scene_page_bytes(s), tet_bytes);
  if (!s.tets.empty() && other < max_bytes * 3 / 4) {
    const std::size_t room = max_bytes - other;
    const std::size_t k = (tet_bytes + room - 1) / room + 1;
    std::vector<std::array<int, 4>> tets;
    std::vector<unsigned char> tissue;
    std::vector<float> angle;
    for (std::size_t t = 0; t < s.tets.size(); t += k) {
      tets.push_back(s.tets[t]);
      tissue.push_back(s.tet_tissue[t]);
      angle.push_back(s.tet_min_dihedral_deg[t]);
    }
    s.tets = std::move(tets);
    s.tet_tissue = std::move(tissue);
    s.tet_min_dihedral_deg = std::move(angle);
    compact_nodes(s);
    if (scene_page_bytes(s) <= max_bytes)
      return "The section shows one tet in " + std::to_string(k) + " (" + std::to_string(s.tets.size()) + " of " +
             std::to_string(s.mesh_tets) + ") to keep this page under " + std::to_string(max_bytes / 1000000) +
             " MB; the mesh files hold every tet.";
  }
  // 2. No section; simplify the surfaces until they fit.
  s.tets.clear();
  s.tet_tissue.clear();
  s.tet_min_dihedral_deg.clear();
  compact_nodes(s);
  const std::size_t before = face_count(s);
  Eigen::Vector3d lo = s.nodes.front(), hi = s.nodes.front();
  for (const auto& p : s.nodes) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  double h = (hi - lo).maxCoeff() / 1000.0;
  while (scene_page_bytes(s) > max_bytes && h > 0) {
    cluster_faces(s, h);
    h *= 1.5;
  }
  return "The surfaces are simplified for display (" + std::to_string(face_count(s)) + " of " + std::to_string(before) +
         " triangles, vertex clustering) and the section is left out to keep this page under " +
         std::to_string(max_bytes / 1000000) + " MB; the mesh files hold the full mesh.";
}

}  // namespace tissuemesh
