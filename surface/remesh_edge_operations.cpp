// RemeshComplex's three edge operations: split at the projected midpoint, collapse onto either
// end, flip; each checked against the intersection guard, the approximation bound and the normals
// before it changes anything.
#include "surface/remesh_complex.h"

#include "core/face_key.h"
#include "surface/triangle_geometry.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>

namespace tissuemesh {
namespace {

/// Flips keep the surface shape: the new pair of triangles must be at least this flat (cos 25 deg),
/// or no less flat than the old pair.
constexpr double kFlipFlatCos = 0.906;
/// A half of a split triangle may turn away from it by at most acos(-0.9) = 154 degrees. Beyond
/// that the projected midpoint has passed the far side of the triangle (a junction curve bending
/// between the edge's ends, a patch creasing there), and the half lies folded flat over its
/// neighbour: two triangles of one patch facing opposite ways, which TetGen's tolerance reads as
/// intersecting. Smaller turns follow real creases, such as the tip of a thin lobule that the
/// long edge bridged, and are kept.
constexpr double kSplitFoldCos = -0.9;

}  // namespace

using Eigen::Vector3d;

bool RemeshComplex::split_point(int a, int b, const std::vector<int>& ts, Vector3d& m) const {
  const int curve = curve_of_edge(a, b);
  m = 0.5 * (x_[a] + x_[b]);
  if (curve >= 0) {
    m = proj_.onto_curve(curve, m);
    return true;
  }
  Vector3d n_ref, n = Vector3d::Zero();
  for (int t : ts) n += normal(t);
  m = proj_.onto_patch(patch_[ts[0]], m, &n_ref);
  return n_ref.dot(n) > 0.0;
}

bool RemeshComplex::split(int a, int b) {
  std::vector<int> ts;
  edge_triangles(a, b, ts);
  const int curve = curve_of_edge(a, b);
  Vector3d m;
  if (!split_point(a, b, ts, m)) return false;
  const int v = static_cast<int>(x_.size());
  std::vector<NewTriangle>& created = scratch().created;
  created.clear();
  for (int t : ts) {
    created.push_back(moved_triangle(t, b, m, v));
    created.push_back(moved_triangle(t, a, m, v));
    // Neither half may face away from the triangle it halves (kSplitFoldCos).
    const Vector3d n = normal(t);
    for (std::size_t k = created.size() - 2; k < created.size(); ++k) {
      const Vector3d nk = area_vector(created[k].p[0], created[k].p[1], created[k].p[2]);
      if (!(nk.norm() > 0.0) || nk.normalized().dot(n) < kSplitFoldCos) return false;
    }
  }
  if (would_fold(ts) || would_intersect(ts)) return false;
  if (curve < 0) {
    kind_.push_back(Kind::Surface);
    owner_.push_back(patch_[ts[0]]);
  } else {
    kind_.push_back(Kind::Curve);
    owner_.push_back(curve);
    curve_edge_.erase(edge_key(a, b));
    curve_edge_[edge_key(a, v)] = curve;
    curve_edge_[edge_key(v, b)] = curve;
    ++curve_edges_[curve];
  }
  x_.push_back(m);
  represents_.emplace_back();
  vt_.emplace_back();
  vertex_alive_.push_back(1);
  ++alive_vertices_;
  for (int t : ts) {
    std::array<int, 3>& tr = tri_[t];
    int i = 0;
    while (!((tr[i] == a || tr[i] == b) && (tr[(i + 1) % 3] == a || tr[(i + 1) % 3] == b))) ++i;
    const int u = tr[i], w = tr[(i + 1) % 3], o = tr[(i + 2) % 3];
    const int n = static_cast<int>(tri_.size());
    tr = {u, v, o};
    tri_.push_back({v, w, o});
    patch_.push_back(patch_[t]);
    tri_alive_.push_back(1);
    std::replace(vt_[w].begin(), vt_[w].end(), t, n);
    vt_[o].push_back(n);
    vt_[v].push_back(t);
    vt_[v].push_back(n);
    index_triangle(t);
    index_triangle(n);
  }
  ++splits;
  return true;
}

bool RemeshComplex::collapse_allowed(int a, int b, const std::vector<int>& ts, const std::vector<int>& na) const {
  if (kind_[a] == Kind::Corner) return false;
  const int curve = curve_of_edge(a, b);
  if (kind_[a] == Kind::Surface && curve >= 0) return false;
  if (kind_[a] == Kind::Curve) {
    if (curve != owner_[a]) return false;
    if (curve_edges_[curve] <= (curve_closed_[curve] ? kMinLoopEdges : 1)) return false;
    // A junction edge (a, w) would become (b, w): refused when that is a junction edge already
    // (two curves between the same two corners, a triangle between them): the two would merge
    // into one edge and one of the curves would lose it.
    for (int w : na)
      if (w != b && curve_of_edge(a, w) >= 0 && curve_of_edge(b, w) >= 0) return false;
  }
  // Link condition: the common neighbours are exactly the opposite vertices of the edge's triangles.
  thread_local std::vector<int> nb, common;  // per thread (partitioned sweeps), kept allocated
  common.clear();
  neighbours(b, nb);
  std::set_intersection(na.begin(), na.end(), nb.begin(), nb.end(), std::back_inserter(common));
  return common.size() == ts.size();
}

bool RemeshComplex::try_collapse(int a, int b, double max_relative) {
  // Per thread (partitioned sweeps), kept allocated: most of a sweep's many attempts fail fast.
  thread_local std::vector<int> ts, na;
  thread_local std::vector<std::array<Vector3d, 3>> ring;
  edge_triangles(a, b, ts);
  if (ts.empty()) return false;
  neighbours(a, na);
  // No edge of the result too long: the test that refuses most attempts (about four in five), so
  // it comes first. Every test here is free of side effects: their order changes no outcome.
  for (int w : na)
    if (w != b && (x_[b] - x_[w]).norm() > max_relative * h(0.5 * (x_[b] + x_[w]))) return false;
  if (!collapse_allowed(a, b, ts, na)) return false;
  if (!move_keeps_normals(a, x_[b], vt_[a], ts)) return false;
  // Approximation: every input vertex a or b stands for stays within max_deviation of the new
  // triangles around b (a removal is checked against what remains, so errors cannot pile up).
  if (deviation() > 0.0) {
    ring.clear();
    for (int v : {a, b})
      for (int t : vt_[v]) {
        if (std::find(ts.begin(), ts.end(), t) != ts.end()) continue;
        std::array<Vector3d, 3> q;
        for (int i = 0; i < 3; ++i) q[i] = tri_[t][i] == a ? x_[b] : x_[tri_[t][i]];
        ring.push_back(q);
      }
    for (int v : {a, b})
      for (int r : represents_[v]) {
        // Within the bound of one ring triangle is enough: stop at the first.
        const bool near = std::any_of(ring.begin(), ring.end(), [&](const std::array<Vector3d, 3>& q) {
          return point_triangle_distance(reference_[r], q[0], q[1], q[2]) <= deviation();
        });
        if (!near) return false;
      }
  }
  // Fidelity: every changed triangle stays close to its patch of the reference and faces the same
  // way there (a triangle bridging the two sides of a thin sheet fails both).
  for (int t : vt_[a]) {
    if (std::find(ts.begin(), ts.end(), t) != ts.end()) continue;
    Vector3d q[3];
    for (int i = 0; i < 3; ++i) q[i] = tri_[t][i] == a ? x_[b] : x_[tri_[t][i]];
    const Vector3d g = (q[0] + q[1] + q[2]) / 3.0, n = area_vector(q[0], q[1], q[2]).normalized();
    Vector3d n_ref;
    const Vector3d on = proj_.onto_patch(patch_[t], g, &n_ref);
    if (n.dot(n_ref) < kMinNormalTurnCos) return false;
    if (deviation() > 0.0 && (on - g).norm() > deviation()) return false;
  }
  // A triangle of a that would coincide with one of b (a pocket between patches closing up).
  for (int t : vt_[a]) {
    if (std::find(ts.begin(), ts.end(), t) != ts.end()) continue;
    for (int u : vt_[b]) {
      int shared = 0;
      for (int w : tri_[t]) shared += w != a && has(u, w);
      if (shared == 2) return false;
    }
  }
  collect_moved(vt_[a], ts, a, x_[b], b);
  // The fold guard reads the triangles beyond the two rings, which may change: try again too.
  if (would_fold(vt_[a]) || would_intersect(vt_[a])) {
    if (tracking_rings_) ring_changed_[a] = ring_changed_[b] = 1;  // the obstacle may go: try again
    return false;
  }
  // Apply.
  if (tracking_rings_)
    for (int t : vt_[a])  // (ts among them)
      for (int w : tri_[t]) ring_changed_[w] = 1;
  for (int t : ts) {
    tri_alive_[t] = 0;
    grid_.remove(t);
    for (int w : tri_[t]) vt_[w].erase(std::remove(vt_[w].begin(), vt_[w].end(), t), vt_[w].end());
  }
  for (int t : vt_[a]) {
    std::replace(tri_[t].begin(), tri_[t].end(), a, b);
    vt_[b].push_back(t);
    index_triangle(t);
  }
  std::sort(vt_[b].begin(), vt_[b].end());
  vt_[a].clear();
  if (kind_[a] == Kind::Curve) {
    const int curve = owner_[a];
    curve_edge_.erase(edge_key(a, b));
    for (int w : na) {
      auto it = curve_edge_.find(edge_key(a, w));
      if (it == curve_edge_.end()) continue;
      curve_edge_.erase(it);
      curve_edge_[edge_key(b, w)] = curve;
    }
    --curve_edges_[curve];
  }
  represents_[b].insert(represents_[b].end(), represents_[a].begin(), represents_[a].end());
  represents_[a].clear();
  vertex_alive_[a] = 0;
  // Counted at once, or by the partitioned sweep once both halves are done (remesh_partition.cpp).
  if (halves_running_) {
    ++scratch().collapsed;
  } else {
    --alive_vertices_;
    ++collapses;
  }
  return true;
}

bool RemeshComplex::collapse_either(int a, int b, double max_relative) {
  // Prefer removing the vertex of lower rank (surface before curve), then the higher index.
  if (kind_[a] < kind_[b] || (kind_[a] == kind_[b] && a > b)) {
    if (try_collapse(a, b, max_relative)) return true;
    return try_collapse(b, a, max_relative);
  }
  if (try_collapse(b, a, max_relative)) return true;
  return try_collapse(a, b, max_relative);
}

bool RemeshComplex::flip_passes_local_tests(int a, int b, FlipQuad& quad) const {
  quad.c = quad.d = -1;
  if (curve_of_edge(a, b) >= 0) return false;
  thread_local std::vector<int> ts;  // per thread (flip_all tests on two), kept allocated
  edge_triangles(a, b, ts);
  if (ts.size() != 2 || patch_[ts[0]] != patch_[ts[1]]) return false;
  const int t1 = ts[0], t2 = ts[1];
  // Orient: t1 holds the directed edge a -> b.
  auto directed = [&](int t, int p, int q) {
    for (int i = 0; i < 3; ++i)
      if (tri_[t][i] == p && tri_[t][(i + 1) % 3] == q) return true;
    return false;
  };
  if (!directed(t1, a, b)) std::swap(a, b);
  if (!directed(t1, a, b) || !directed(t2, b, a)) return false;
  auto third = [&](int t, int p, int q) {
    for (int w : tri_[t])
      if (w != p && w != q) return w;
    return -1;
  };
  const int c = third(t1, a, b), d = third(t2, a, b);
  quad = {a, b, c, d, t1, t2};
  if (c == d || edge_exists(c, d)) return false;
  // A flip takes a triangle from a and from b; neither may be left with three (such a vertex
  // bounds its triangles' smallest angle by half that of the triangle around them).
  if (vt_[a].size() <= 4 || vt_[b].size() <= 4) return false;
  const Vector3d &pa = x_[a], &pb = x_[b], &pc = x_[c], &pd = x_[d];
  // Delaunay: flip when the opposite angles sum beyond pi, i.e. the new diagonal gives the
  // larger smallest angle.
  if (angle_at_c(pa, pb, pc) + angle_at_c(pb, pa, pd) <= M_PI + 1e-9) return false;
  if (std::min(min_angle(pa, pd, pc), min_angle(pd, pb, pc)) <= std::min(min_angle(pa, pb, pc), min_angle(pb, pa, pd)))
    return false;
  const Vector3d n1 = area_vector(pa, pb, pc).normalized(), n2 = area_vector(pb, pa, pd).normalized();
  const Vector3d m1 = area_vector(pa, pd, pc).normalized(), m2 = area_vector(pd, pb, pc).normalized();
  if (m1.dot(m2) < std::min(n1.dot(n2), kFlipFlatCos)) return false;
  const Vector3d mean = (n1 + n2).normalized();
  return m1.dot(mean) >= kMinNormalTurnCos && m2.dot(mean) >= kMinNormalTurnCos;
}

bool RemeshComplex::try_flip(int a_, int b_, FlipQuad* flipped) {
  FlipQuad q;
  if (!flip_passes_local_tests(a_, b_, q)) return false;
  const int a = q.a, b = q.b, c = q.c, d = q.d, t1 = q.t1, t2 = q.t2;
  const Vector3d &pa = x_[a], &pb = x_[b], &pc = x_[c], &pd = x_[d];
  scratch().created = {{{a, d, c}, {pa, pd, pc}, patch_[t1]}, {{d, b, c}, {pd, pb, pc}, patch_[t1]}};
  if (would_fold({t1, t2}) || would_intersect({t1, t2})) return false;
  tri_[t1] = {a, d, c};
  tri_[t2] = {d, b, c};
  index_triangle(t1);
  index_triangle(t2);
  vt_[b].erase(std::remove(vt_[b].begin(), vt_[b].end(), t1), vt_[b].end());
  vt_[a].erase(std::remove(vt_[a].begin(), vt_[a].end(), t2), vt_[a].end());
  vt_[d].push_back(t1);
  vt_[c].push_back(t2);
  ++flips;
  if (flipped) *flipped = q;
  return true;
}

}  // namespace tissuemesh
