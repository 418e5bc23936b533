// Why: the extracted surface has hundreds of thousands of triangles, and CGAL's self_intersections
// per tissue boundary tests every interface triangle twice, so the extraction uses the grid search
// (PairSearch::Grid) and, after its unfolding moved a few vertices, recheck_after_moves instead of
// a full check. Both apply CGAL's rule (surface/triangle_intersection.h), and the remeshed surface
// is still checked by CGAL itself (PairSearch::Cgal), independently of the remesher's own test.
#include "surface/surface_checks.h"

#include "core/face_key.h"
#include "surface/intersecting_pairs.h"
#include "surface/triangle_intersection.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Surface_mesh.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <map>
#include <stdexcept>

namespace tissuemesh {
namespace {

namespace PMP = CGAL::Polygon_mesh_processing;
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Mesh = CGAL::Surface_mesh<Kernel::Point_3>;

/// Edge usage of oriented triangles: open, non-manifold and misoriented edge counts.
void count_edges(const std::vector<std::array<int, 3>>& tris, TissueSurfaceCheck& c) {
  std::vector<std::pair<std::uint64_t, int>> uses;  // key, +1 if stored min->max else -1
  uses.reserve(3 * tris.size());
  for (const auto& t : tris)
    for (int e = 0; e < 3; ++e) {
      const int a = t[e], b = t[(e + 1) % 3];
      uses.emplace_back(edge_key(a, b), a < b ? 1 : -1);
    }
  std::sort(uses.begin(), uses.end());
  for (std::size_t i = 0; i < uses.size();) {
    std::size_t j = i;
    int balance = 0;
    while (j < uses.size() && uses[j].first == uses[i].first) balance += uses[j++].second;
    const std::size_t n = j - i;
    if (n == 1) ++c.open_edges;
    else if (n > 2) ++c.nonmanifold_edges;
    else if (balance != 0) ++c.misoriented_edges;
    i = j;
  }
}

/// Vertices 0..n-1 of a closed, oriented triangle set (count_edges found nothing) whose triangles
/// form more than one fan: the boundary touches itself there. Each triangle (a, b, c) adds the link
/// edge b -> c at a (and so on); with every edge used once in each direction the link edges at a
/// vertex form disjoint cycles, and a manifold vertex has exactly one. (CGAL's
/// is_polygon_soup_a_polygon_mesh tests the same plus what count_edges already did, and costs
/// about as much as the rest of a check of an extracted surface.)
std::size_t count_nonmanifold_vertices(const std::vector<std::array<int, 3>>& tris, std::size_t n) {
  std::vector<std::size_t> start(n + 1, 0);
  for (const auto& t : tris)
    for (int v : t) ++start[static_cast<std::size_t>(v) + 1];
  for (std::size_t v = 0; v < n; ++v) start[v + 1] += start[v];
  std::vector<std::array<int, 2>> link(start[n]);
  std::vector<std::size_t> fill(start.begin(), start.end() - 1);
  for (const auto& t : tris)
    for (int k = 0; k < 3; ++k) link[fill[static_cast<std::size_t>(t[k])]++] = {t[(k + 1) % 3], t[(k + 2) % 3]};
  std::size_t bad = 0;
  for (std::size_t v = 0; v < n; ++v) {
    const auto first = link.begin() + static_cast<std::ptrdiff_t>(start[v]), last = link.begin() + static_cast<std::ptrdiff_t>(start[v + 1]);
    if (first == last) continue;
    std::size_t steps = 1;
    for (int at = (*first)[1]; at != (*first)[0] && steps <= start[v + 1] - start[v]; ++steps) {
      const auto next = std::find_if(first, last, [at](const std::array<int, 2>& e) { return e[0] == at; });
      if (next == last) break;
      at = (*next)[1];
    }
    bad += steps != start[v + 1] - start[v];
  }
  return bad;
}

/// Intersecting pairs of a closed, oriented, vertex-manifold triangle set, as positions in
/// `polygons` (a degenerate triangle f is reported as the pair (f, f)).
void intersecting_pairs(const std::vector<Kernel::Point_3>& points, const std::vector<std::array<int, 3>>& polygons,
                        std::vector<std::pair<int, int>>& out) {
  Mesh mesh;
  // Faces are created in polygon order, so face index i is polygons[i].
  PMP::polygon_soup_to_polygon_mesh(points, polygons, mesh);
  std::vector<std::pair<Mesh::Face_index, Mesh::Face_index>> pairs;
  PMP::self_intersections(faces(mesh), mesh, std::back_inserter(pairs));
  for (const auto& [f, g] : pairs) out.emplace_back(static_cast<int>(f.idx()), static_cast<int>(g.idx()));
}

/// Volume enclosed by outward triangles (divergence theorem), mm^3; summed in triangle order.
double enclosed_volume(const std::vector<Eigen::Vector3d>& points, const std::vector<std::array<int, 3>>& tris) {
  double volume = 0.0;
  for (const auto& t : tris) {
    const Eigen::Vector3d &a = points[t[0]], &b = points[t[1]], &d = points[t[2]];
    volume += a.dot(b.cross(d)) / 6.0;
  }
  return volume;
}

/// Tissue `id`'s boundary triangles, oriented outward (global vertex ids), and their global ids.
std::vector<std::array<int, 3>> outward_boundary(const TriSurface& s, int id, std::vector<int>& ids) {
  std::vector<char> reversed;
  s.tissue_boundary(id, ids, reversed);
  std::vector<std::array<int, 3>> tris;
  tris.reserve(ids.size());
  for (std::size_t k = 0; k < ids.size(); ++k) {
    auto t = s.triangles[static_cast<std::size_t>(ids[k])];
    if (reversed[k]) std::swap(t[1], t[2]);
    tris.push_back(t);
  }
  return tris;
}

/// Closed box of a triangle's corners (the candidate filter of CGAL's self_intersections).
struct Box3 {
  Eigen::Vector3d lo, hi;
  explicit Box3(const TrianglePoints& p) : lo(p[0].cwiseMin(p[1]).cwiseMin(p[2])), hi(p[0].cwiseMax(p[1]).cwiseMax(p[2])) {}
  bool overlaps(const Box3& o) const { return (lo.array() <= o.hi.array()).all() && (o.lo.array() <= hi.array()).all(); }
};

/// Per tissue: topology and volume; with `cgal_pairs`, also its intersecting pairs (global ids) by
/// CGAL, else intersecting_pairs is 0 when the boundary can be checked (closed, oriented and
/// vertex-manifold) and -1 when not.
TissueSurfaceCheck tissue_check(const TriSurface& s, int id, bool cgal_pairs, std::vector<std::pair<int, int>>* pairs) {
  TissueSurfaceCheck c;
  c.tissue_id = id;
  c.name = s.tissue_names[static_cast<std::size_t>(id - 1)];
  std::vector<int> ids;
  std::vector<std::array<int, 3>> tris = outward_boundary(s, id, ids);
  // Global vertex -> local index, numbered in ascending global order (deterministic); -1 = not
  // on this boundary.
  std::vector<int> local(s.points.size(), -1);
  for (const auto& t : tris)
    for (int v : t) local[static_cast<std::size_t>(v)] = 0;
  c.triangles = tris.size();
  c.vertices = static_cast<std::size_t>(std::count(local.begin(), local.end(), 0));
  count_edges(tris, c);
  c.volume_mm3 = enclosed_volume(s.points, tris);
  if (c.closed_and_oriented() && !tris.empty()) {
    std::vector<Kernel::Point_3> points;
    points.reserve(c.vertices);
    for (std::size_t v = 0; v < local.size(); ++v) {
      if (local[v] < 0) continue;
      local[v] = static_cast<int>(points.size());
      points.emplace_back(s.points[v][0], s.points[v][1], s.points[v][2]);
    }
    for (auto& t : tris)
      for (int& v : t) v = local[static_cast<std::size_t>(v)];
    c.nonmanifold_vertices = count_nonmanifold_vertices(tris, points.size());
    if (c.nonmanifold_vertices == 0 && !cgal_pairs) {
      c.intersecting_pairs = 0;
    } else if (c.nonmanifold_vertices == 0) {
      std::vector<std::pair<int, int>> found;
      intersecting_pairs(points, tris, found);
      c.intersecting_pairs = static_cast<long long>(found.size());
      if (pairs)
        for (const auto& [a, b] : found) pairs->emplace_back(ids[static_cast<std::size_t>(a)], ids[static_cast<std::size_t>(b)]);
    }
  }
  return c;
}

}  // namespace

bool SurfaceCheckReport::valid() const {
  for (const auto& t : tissues)
    if (!t.closed_and_oriented() || t.intersecting_pairs != 0) return false;
  return duplicate_triangles == 0 && junction_edges_off_junction == 0;
}

SurfaceCheckReport check_surface(const TriSurface& s, std::vector<int>* intersecting, PairSearch search) {
  SurfaceCheckReport report;
  // Tissues are independent: checked in parallel (the fat's boundary dominates, so two threads).
  const int tissues = static_cast<int>(s.tissue_names.size());
  report.tissues.resize(static_cast<std::size_t>(tissues));
  std::vector<std::vector<std::pair<int, int>>> pairs(static_cast<std::size_t>(tissues));
  const bool cgal = search == PairSearch::Cgal;
#pragma omp parallel for schedule(dynamic, 1) num_threads(2)
  for (int id = 1; id <= tissues; ++id)
    report.tissues[static_cast<std::size_t>(id - 1)] =
        tissue_check(s, id, cgal, intersecting ? &pairs[static_cast<std::size_t>(id - 1)] : nullptr);
  if (!cgal) {
    // One pass over all triangles; a pair counts in each checked tissue both triangles bound.
    std::vector<char> checked(static_cast<std::size_t>(tissues));
    for (int id = 1; id <= tissues; ++id) checked[static_cast<std::size_t>(id - 1)] = report.tissues[static_cast<std::size_t>(id - 1)].intersecting_pairs == 0;
    for (const auto& [t, u] : intersecting_pairs_by_grid(s, checked)) {
      const auto &lt = s.labels[static_cast<std::size_t>(t)], &lu = s.labels[static_cast<std::size_t>(u)];
      for (int id : lt)
        if (id > 0 && checked[static_cast<std::size_t>(id - 1)] && (id == lu[0] || id == lu[1])) {
          ++report.tissues[static_cast<std::size_t>(id - 1)].intersecting_pairs;
          pairs[static_cast<std::size_t>(id - 1)].emplace_back(t, u);
        }
    }
  }
  if (intersecting) {
    intersecting->clear();
    for (const auto& tissue_pairs : pairs)
      for (const auto& [a, b] : tissue_pairs) intersecting->insert(intersecting->end(), {a, b});
    std::sort(intersecting->begin(), intersecting->end());
    intersecting->erase(std::unique(intersecting->begin(), intersecting->end()), intersecting->end());
  }

  std::vector<std::array<int, 3>> sorted = s.triangles;
  for (auto& t : sorted) std::sort(t.begin(), t.end());
  std::sort(sorted.begin(), sorted.end());
  for (std::size_t i = 1; i < sorted.size(); ++i) report.duplicate_triangles += sorted[i] == sorted[i - 1];

  std::map<std::uint64_t, int> edge_triangles;
  for (const auto& j : s.junctions)
    for (std::size_t k = 0; k + 1 < j.size(); ++k) edge_triangles.emplace(edge_key(j[k], j[k + 1]), 0);
  for (const auto& t : s.triangles)
    for (int e = 0; e < 3; ++e) {
      auto it = edge_triangles.find(edge_key(t[e], t[(e + 1) % 3]));
      if (it != edge_triangles.end()) ++it->second;
    }
  report.junction_edges = edge_triangles.size();
  for (const auto& [key, n] : edge_triangles) report.junction_edges_off_junction += n < 3;
  return report;
}

SurfaceCheckReport recheck_after_moves(const TriSurface& s, const SurfaceCheckReport& previous,
                                       const std::vector<int>& previous_intersecting, const std::vector<int>& moved,
                                       std::vector<int>* intersecting) {
  std::vector<char> is_moved(s.points.size(), 0);
  for (int v : moved) is_moved[static_cast<std::size_t>(v)] = 1;
  auto changed = [&](const std::array<int, 3>& t) {
    return is_moved[static_cast<std::size_t>(t[0])] || is_moved[static_cast<std::size_t>(t[1])] ||
           is_moved[static_cast<std::size_t>(t[2])];
  };
  for (int t : previous_intersecting)
    if (!changed(s.triangles[static_cast<std::size_t>(t)]))
      throw std::invalid_argument("recheck_after_moves: intersecting triangle " + std::to_string(t) +
                                  " has no moved vertex");
  SurfaceCheckReport report = previous;  // topology unchanged: counts, duplicates, junction edges
  std::vector<int> found;
  for (TissueSurfaceCheck& c : report.tissues) {
    std::vector<int> ids;
    const std::vector<std::array<int, 3>> tris = outward_boundary(s, c.tissue_id, ids);
    c.volume_mm3 = enclosed_volume(s.points, tris);
    if (c.intersecting_pairs < 0) continue;  // not checked before (open or non-manifold): still not
    // Every pair of unchanged triangles was tested before and found apart (a triangle of an
    // intersecting pair has a moved vertex), so only pairs with a changed triangle can intersect.
    // CGAL's rule: a degenerate (collinear) triangle is the pair (f, f) and meets nothing else.
    auto points = [&](std::size_t k) {
      const auto& t = tris[k];
      return TrianglePoints{s.points[static_cast<std::size_t>(t[0])], s.points[static_cast<std::size_t>(t[1])],
                            s.points[static_cast<std::size_t>(t[2])]};
    };
    std::vector<std::size_t> moving;  // positions in tris of changed, non-degenerate triangles
    std::vector<char> is_moving(tris.size(), 0);
    c.intersecting_pairs = 0;
    for (std::size_t k = 0; k < tris.size(); ++k) {
      if (!changed(tris[k])) continue;
      const TrianglePoints p = points(k);
      if (triangle_is_degenerate(p)) {
        ++c.intersecting_pairs;
        found.push_back(ids[k]);
      } else {
        moving.push_back(k);
        is_moving[k] = 1;
      }
    }
    if (moving.empty()) continue;
    std::vector<Box3> boxes;
    for (std::size_t k : moving) boxes.emplace_back(points(k));
    Box3 all = boxes.front();
    for (const Box3& b : boxes) all.lo = all.lo.cwiseMin(b.lo), all.hi = all.hi.cwiseMax(b.hi);
    for (std::size_t u = 0; u < tris.size(); ++u) {
      const TrianglePoints pu = points(u);
      const Box3 bu(pu);
      if (!bu.overlaps(all) || (changed(tris[u]) && !is_moving[u])) continue;  // degenerate: no box
      for (std::size_t i = 0; i < moving.size(); ++i) {
        const std::size_t k = moving[i];
        if (k == u || (is_moving[u] && u < k) || !boxes[i].overlaps(bu)) continue;  // each pair once
        if (!triangles_intersect(points(k), tris[k], pu, tris[u])) continue;
        ++c.intersecting_pairs;
        found.insert(found.end(), {ids[k], ids[u]});
      }
    }
  }
  if (intersecting) {
    std::sort(found.begin(), found.end());
    found.erase(std::unique(found.begin(), found.end()), found.end());
    *intersecting = std::move(found);
  }
  return report;
}

}  // namespace tissuemesh
