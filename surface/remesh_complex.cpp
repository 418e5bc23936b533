// Why: the intersection guard makes validity a property of every operation rather than a hope
// for the result: where a thin sheet (the skin, an fgt sheet) would be crossed, the operations are
// refused and the sheet keeps the vertices it needs. The approximation bound does the same for
// shape: a removal is checked against what remains, so errors cannot pile up. grade_stuck_edges
// enters only edges between two junction vertices: an edge with a surface vertex can still
// lengthen when that vertex moves, and a short edge held by a thin sheet, once entered, refines
// the sheet into ever shorter edges and slivers.
#include "surface/remesh_complex.h"

#include "core/face_key.h"
#include "core/union_find.h"
#include "surface/run_at_once.h"
#include "surface/triangle_geometry.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>

namespace tissuemesh {
namespace {

using Eigen::Vector3d;

/// The approximation bound is at least this fraction of the edge length L.
constexpr double kDeviationPerEdge = 0.25;
/// Size cap around stuck edges (surface/graded_size_cap.h): h = 1.5 times the stuck edge there, so
/// an isosceles triangle on it whose sides reach the split threshold 4/3 h still has an apex angle
/// of 2 asin(1 / (2 * 1.5 * 4/3)) = 29 degrees (1.93 gave 30 degrees only for sides of exactly h);
/// the size then grows by 0.4 mm per mm, so neighbouring triangles differ in size by a factor 1.4
/// at most. Tuned on the phantom's two shipped budgets (the count of angles under 30 degrees moves
/// by a few between neighbouring factors): a tuned value, not a threshold.
constexpr double kCapFactor = 1.5;
constexpr double kCapGradation = 0.4;
/// The cap's floor as a fraction of options.max_deviation_mm (RemeshComplex::s): below a quarter
/// voxel diagonal no edge means anything. The phantom's shipped budgets do not reach it.
constexpr double kCapFloorOfDeviation = 0.5;
/// edges() lists the two halves of the triangle list on two threads from this many triangles on
/// (a smaller list takes less time than starting the threads).
constexpr std::size_t kParallelEdgesFrom = 20000;

/// The input's bounding box widened by a tenth of its diagonal on every side (a unit box for an
/// empty input): the remesher's vertices stay on or near the input surface, so the grids' cells
/// cover them (a grid still works beyond its region, only with more candidates per query).
Eigen::AlignedBox3d widened_bounds(const TriSurface& in) {
  Eigen::AlignedBox3d box;
  for (const Vector3d& p : in.points) box.extend(p);
  if (box.isEmpty()) return Eigen::AlignedBox3d(Vector3d::Zero(), Vector3d::Ones());
  const Vector3d margin = Vector3d::Constant(0.1 * box.diagonal().norm() + 1.0);
  return Eigen::AlignedBox3d(box.min() - margin, box.max() + margin);
}


}  // namespace

RemeshComplex::RemeshComplex(const TriSurface& in, const SurfaceProjection& projection, const RemeshOptions& options)
    : proj_(projection),
      size_(options.relative_size),
      max_edge_(options.max_edge_mm),
      region_(widened_bounds(in)),
      cap_(kCapFactor, kCapGradation, region_),
      max_deviation_(options.max_deviation_mm),
      fold_guard_(options.fold_guard),
      threads_(std::clamp(options.threads, 1, 2)) {
  x_ = in.points;
  reference_ = in.points;
  represents_.resize(x_.size());
  for (int v = 0; v < static_cast<int>(x_.size()); ++v) represents_[v] = {v};
  tri_ = in.triangles;
  patch_ = projection.patches().patch_of_triangle;
  tri_alive_.assign(tri_.size(), 1);
  vt_.resize(x_.size());
  for (int t = 0; t < static_cast<int>(tri_.size()); ++t)
    for (int v : tri_[t]) vt_[v].push_back(t);
  curve_edges_.assign(in.junctions.size(), 0);
  curve_closed_.assign(in.junctions.size(), 0);
  std::vector<int> degree(x_.size(), 0), end(x_.size(), 0), curve_of(x_.size(), -1), curves_at(x_.size(), 0);
  for (int c = 0; c < static_cast<int>(in.junctions.size()); ++c) {
    const std::vector<int>& line = in.junctions[c];
    curve_closed_[c] = line.size() > 2 && line.front() == line.back();
    if (!curve_closed_[c]) {
      ++end[line.front()];
      ++end[line.back()];
    }
    for (std::size_t i = 0; i + 1 < line.size(); ++i) {
      curve_edge_[edge_key(line[i], line[i + 1])] = c;
      ++curve_edges_[c];
      for (int v : {line[i], line[i + 1]}) {
        ++degree[v];
        if (curve_of[v] != c) ++curves_at[v];
        curve_of[v] = c;
      }
    }
  }
  kind_.resize(x_.size());
  owner_.resize(x_.size());
  for (std::size_t v = 0; v < x_.size(); ++v) {
    if (degree[v] == 0) {
      kind_[v] = Kind::Surface;
      owner_[v] = vt_[v].empty() ? -1 : patch_[vt_[v][0]];
      for (int t : vt_[v])
        if (patch_[t] != owner_[v]) kind_[v] = Kind::Corner;  // a pinch: never move it
    } else if (degree[v] == 2 && end[v] == 0 && curves_at[v] == 1) {
      kind_[v] = Kind::Curve;
      owner_[v] = curve_of[v];
    } else {
      kind_[v] = Kind::Corner;
      owner_[v] = -1;
    }
  }
  vertex_alive_.assign(x_.size(), 1);
  for (std::size_t v = 0; v < x_.size(); ++v)
    if (vt_[v].empty()) vertex_alive_[v] = 0;
  alive_vertices_ = std::count(vertex_alive_.begin(), vertex_alive_.end(), 1);
}

double RemeshComplex::deviation() const {
  if (!(max_deviation_ > 0.0)) return 0.0;
  return std::max(max_deviation_, kDeviationPerEdge * L) * slack_ * deviation_scale_;
}

std::size_t RemeshComplex::corners() const {
  std::size_t n = 0;
  for (std::size_t v = 0; v < x_.size(); ++v) n += vertex_alive_[v] && kind_[v] == Kind::Corner;
  return n;
}

RemeshComplex::VertexFloor RemeshComplex::vertex_floor() const {
  VertexFloor f;
  f.corners = corners();
  f.loop_vertices = kMinLoopEdges;
  for (std::size_t c = 0; c < curve_closed_.size(); ++c) f.closed_curves += curve_closed_[c] && curve_edges_[c] > 0;
  // Pieces: vertices joined by live triangles; a piece whose vertices are all surface vertices is
  // a closed surface without junctions.
  std::vector<int> parent = singleton_sets(x_.size());
  auto root = [&](int v) { return find_root(parent, v); };
  for (std::size_t t = 0; t < tri_.size(); ++t)
    if (tri_alive_[t])
      for (int i = 1; i < 3; ++i) parent[root(tri_[t][i])] = root(tri_[t][0]);
  std::vector<char> has_junction(x_.size(), 0), seen(x_.size(), 0);
  for (std::size_t v = 0; v < x_.size(); ++v)
    if (vertex_alive_[v] && kind_[v] != Kind::Surface) has_junction[root(static_cast<int>(v))] = 1;
  for (std::size_t v = 0; v < x_.size(); ++v) {
    if (!vertex_alive_[v]) continue;
    const int r = root(static_cast<int>(v));
    if (seen[r]) continue;
    seen[r] = 1;
    f.closed_pieces += !has_junction[r];
  }
  return f;
}

double RemeshComplex::s(const Vector3d& p) const {
  double s0 = size_ ? size_(p) : 1.0;
  if (max_edge_) s0 = std::min(s0, thickness_scale * max_edge_(p) / L);
  // The cap never goes below kCapFloorOfDeviation of the deviation bound (a quarter of a voxel
  // diagonal in the pipeline): around two junction corners a fraction of a voxel apart, each
  // round's splits left shorter stuck edges whose caps asked for shorter edges again, down to
  // 0.0001 mm and a knot of hundreds of triangles that TetGen filled with flat tets.
  return cap_.size() == 0 ? s0 : std::min(s0, std::max(cap_(p), kCapFloorOfDeviation * max_deviation_) / L);
}

double RemeshComplex::thin_vertex_demand() const {
  if (!max_edge_) return 0.0;
  double sum = 0.0;
  for (std::size_t t = 0; t < tri_.size(); ++t) {
    if (!tri_alive_[t]) continue;
    const Vector3d &a = x_[tri_[t][0]], &b = x_[tri_[t][1]], &c = x_[tri_[t][2]];
    const double bound = thickness_scale * max_edge_((a + b + c) / 3.0);
    if (bound < L) sum += area_vector(a, b, c).norm() * 2.0 / (std::sqrt(3.0) * bound * bound);
  }
  return sum;
}

double RemeshComplex::weighted_area() const {
  double sum = 0.0;
  for (std::size_t t = 0; t < tri_.size(); ++t) {
    if (!tri_alive_[t]) continue;
    const Vector3d &a = x_[tri_[t][0]], &b = x_[tri_[t][1]], &c = x_[tri_[t][2]];
    const double st = s((a + b + c) / 3.0);
    sum += area_vector(a, b, c).norm() / (st * st);
  }
  return sum;
}

std::vector<std::array<int, 2>> RemeshComplex::edges() const {
  // Each edge once, from its lowest-indexed live triangle: a triangle's edges depend on nothing
  // but its own ring, so the two halves of the triangle list are listed on two threads and joined
  // in order (the list is the one a single pass makes).
  auto list = [this](std::size_t begin, std::size_t end, std::vector<std::array<int, 2>>& out) {
    for (std::size_t t = begin; t < end; ++t) {
      if (!tri_alive_[t]) continue;
      for (int i = 0; i < 3; ++i) {
        const int a = tri_[t][i], b = tri_[t][(i + 1) % 3];
        bool first = true;
        for (int u : vt_[a])
          if (u < static_cast<int>(t) && has(u, b)) first = false;
        if (first) out.push_back({std::min(a, b), std::max(a, b)});
      }
    }
  };
  std::vector<std::array<int, 2>> out, second;
  out.reserve(3 * tri_.size() / 2 + 16);  // a closed surface has 3/2 edges per triangle
  if (tri_.size() < kParallelEdgesFrom) {
    list(0, tri_.size(), out);
    return out;
  }
  const std::size_t half = tri_.size() / 2;
  second.reserve(3 * half / 2 + 16);
  run_at_once([&] { list(0, half, out); }, [&] { list(half, tri_.size(), second); }, threads_);
  out.insert(out.end(), second.begin(), second.end());
  return out;
}

bool RemeshComplex::edge_exists(int a, int b) const {
  if (!vertex_alive_[a] || !vertex_alive_[b]) return false;
  for (int t : vt_[a])
    if (has(t, b)) return true;
  return false;
}

void RemeshComplex::edge_triangles(int a, int b, std::vector<int>& out) const {
  out.clear();
  for (int t : vt_[a])
    if (has(t, b)) out.push_back(t);
}

void RemeshComplex::neighbours(int v, std::vector<int>& out) const {
  out.clear();
  for (int t : vt_[v])
    for (int w : tri_[t])
      if (w != v) out.push_back(w);
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
}

int RemeshComplex::curve_of_edge(int a, int b) const {
  auto it = curve_edge_.find(edge_key(a, b));
  return it == curve_edge_.end() ? -1 : it->second;
}

RemeshComplex::Vector3d RemeshComplex::normal(int t) const {
  return area_vector(x_[tri_[t][0]], x_[tri_[t][1]], x_[tri_[t][2]]).normalized();
}

RemeshComplex::Vector3d RemeshComplex::moved_normal(int t, int v, const Vector3d& p) const {
  Vector3d q[3];
  for (int i = 0; i < 3; ++i) q[i] = tri_[t][i] == v ? p : x_[tri_[t][i]];
  const Vector3d n = area_vector(q[0], q[1], q[2]);
  const double len = n.norm();
  return len > 0.0 ? Vector3d(n / len) : Vector3d::Zero();
}

bool RemeshComplex::move_keeps_normals(int v, const Vector3d& p, const std::vector<int>& tris, const std::vector<int>& skip) const {
  for (int t : tris) {
    if (std::find(skip.begin(), skip.end(), t) != skip.end()) continue;
    if (moved_normal(t, v, p).dot(normal(t)) < kMinNormalTurnCos) return false;
  }
  return true;
}

double RemeshComplex::ring_distance(int r, int w, int v, const Vector3d& p) const {
  double d = INFINITY;
  for (int t : vt_[w]) {
    Vector3d q[3];
    for (int i = 0; i < 3; ++i) q[i] = tri_[t][i] == v ? p : x_[tri_[t][i]];
    d = std::min(d, point_triangle_distance(reference_[r], q[0], q[1], q[2]));
    if (d <= deviation()) break;
  }
  return d;
}

bool RemeshComplex::keeps_represented(int v, const Vector3d& p, std::vector<std::array<int, 2>>* handoff) const {
  if (!(deviation() > 0.0) || represents_[v].empty()) return true;
  std::vector<int> nb;
  if (handoff) {
    handoff->clear();
    neighbours(v, nb);
  }
  for (int r : represents_[v]) {
    if (ring_distance(r, v, v, p) <= deviation()) continue;
    const auto w = std::find_if(nb.begin(), nb.end(), [&](int u) { return ring_distance(r, u, v, p) <= deviation(); });
    if (w == nb.end()) return false;
    handoff->push_back({r, *w});
  }
  return true;
}

RemeshComplex::NewTriangle RemeshComplex::moved_triangle(int t, int v, const Vector3d& p, int id) const {
  NewTriangle n;
  n.patch = patch_[t];
  for (int i = 0; i < 3; ++i) {
    const bool moved = tri_[t][i] == v;
    n.v[i] = moved ? id : tri_[t][i];
    n.p[i] = moved ? p : x_[tri_[t][i]];
  }
  return n;
}

void RemeshComplex::collect_moved(const std::vector<int>& tris, const std::vector<int>& skip, int v, const Vector3d& p,
                                  int id) {
  std::vector<NewTriangle>& created = scratch().created;
  created.clear();
  for (int t : tris)
    if (std::find(skip.begin(), skip.end(), t) == skip.end()) created.push_back(moved_triangle(t, v, p, id));
}

double RemeshComplex::fold_cos_before(const std::vector<int>& replaced) const {
  double worst = 1.0;
  for (int t : replaced) {
    const Vector3d n = normal(t);
    for (int i = 0; i < 3; ++i) {
      const int u = tri_[t][i], w = tri_[t][(i + 1) % 3];
      for (int o : vt_[u])
        if (o != t && tri_alive_[o] && patch_[o] == patch_[t] && has(o, w)) worst = std::min(worst, n.dot(normal(o)));
    }
  }
  return worst;
}

double RemeshComplex::fold_cos_after(const std::vector<int>& replaced) {
  const std::vector<NewTriangle>& created = scratch().created;
  const int known = static_cast<int>(vt_.size());  // a split's new vertex has no triangle list yet
  auto holds = [](const NewTriangle& c, int x) { return c.v[0] == x || c.v[1] == x || c.v[2] == x; };
  double worst = 1.0;
  for (std::size_t i = 0; i < created.size(); ++i) {
    const NewTriangle& c = created[i];
    const Vector3d a = area_vector(c.p[0], c.p[1], c.p[2]);
    if (!(a.norm() > 0.0)) continue;  // degenerate: the normal guards refuse it
    const Vector3d n = a.normalized();
    for (int e = 0; e < 3; ++e) {
      const int u = c.v[e], w = c.v[(e + 1) % 3];
      for (std::size_t j = 0; j < created.size(); ++j) {
        const NewTriangle& d = created[j];
        if (j == i || d.patch != c.patch || !holds(d, u) || !holds(d, w)) continue;
        const Vector3d b = area_vector(d.p[0], d.p[1], d.p[2]);
        if (b.norm() > 0.0) worst = std::min(worst, n.dot(b.normalized()));
      }
      const int from = u < known ? u : w;
      if (from >= known) continue;
      for (int o : vt_[from]) {
        if (!tri_alive_[o] || patch_[o] != c.patch || !has(o, from == u ? w : u)) continue;
        if (std::find(replaced.begin(), replaced.end(), o) != replaced.end()) continue;
        worst = std::min(worst, n.dot(normal(o)));
      }
    }
  }
  return worst;
}

bool RemeshComplex::would_fold(const std::vector<int>& replaced) {
  if (!fold_guard_) return false;
  const double after = fold_cos_after(replaced);
  return after < kFoldCos && after < fold_cos_before(replaced);
}

double RemeshComplex::ring_min_angle(int v, const Vector3d& p) const {
  double m = INFINITY;
  for (int t : vt_[v]) {
    const NewTriangle q = moved_triangle(t, v, p, v);
    m = std::min(m, min_angle(q.p[0], q.p[1], q.p[2]));
  }
  return m;
}

RemeshComplex::RingShape RemeshComplex::ring_shape(int v, const Vector3d& p, double poor_angle_rad) const {
  RingShape r{INFINITY, INFINITY, 0, 0.0};
  for (int t : vt_[v]) {
    const NewTriangle q = moved_triangle(t, v, p, v);
    for (double a : triangle_angles(q.p[0], q.p[1], q.p[2])) {
      r.min_angle = std::min(r.min_angle, a);
      r.poor_angles += a < poor_angle_rad;
    }
    const double quality = triangle_quality(q.p[0], q.p[1], q.p[2]);
    r.min_quality = std::min(r.min_quality, quality);
    r.quality_sum += quality;
  }
  return r;
}

double RemeshComplex::shorter_curve_edge(int v, const Vector3d& p) const {
  std::vector<int> nb;
  neighbours(v, nb);
  double m = INFINITY;
  for (int w : nb)
    if (curve_of_edge(v, w) == owner_[v]) m = std::min(m, (x_[w] - p).norm());
  return m;
}

RemeshComplex::Vector3d RemeshComplex::vertex_normal(int v) const {
  Vector3d n = Vector3d::Zero();
  for (int t : vt_[v]) n += area_vector(x_[tri_[t][0]], x_[tri_[t][1]], x_[tri_[t][2]]);
  return n.norm() == 0.0 ? n : Vector3d(n.normalized());
}

bool RemeshComplex::tangential_target(int v, const Vector3d& n, const Vector3d& goal, Vector3d& target) const {
  if (n.isZero()) return false;
  const Vector3d d = goal - x_[v];
  Vector3d n_ref;
  target = proj_.onto_patch(owner_[v], x_[v] + d - n.dot(d) * n, &n_ref);
  return n_ref.dot(n) > 0.0;  // else the far side of a thin sheet: stay
}

bool RemeshComplex::try_move(int v, const Vector3d& p, bool handoff) {
  std::vector<std::array<int, 2>> handed;
  if (!move_keeps_normals(v, p, vt_[v], {}) || !keeps_represented(v, p, handoff ? &handed : nullptr)) return false;
  collect_moved(vt_[v], {}, v, p, v);
  if (would_fold(vt_[v]) || would_intersect(vt_[v])) return false;
  for (const auto& [r, w] : handed) {
    represents_[v].erase(std::find(represents_[v].begin(), represents_[v].end(), r));
    represents_[w].push_back(r);
  }
  x_[v] = p;
  for (int t : vt_[v]) index_triangle(t);
  return true;
}

}  // namespace tissuemesh
