// The sweeps of RemeshComplex over the whole complex (split, collapse, flip, relaxation,
// angle-improving and quality-raising smoothing, budget matching): which edges or vertices each
// visits, in index order, and which local operation (surface/remesh_complex.cpp) it applies there.
#include "surface/remesh_complex.h"

#include "surface/run_at_once.h"
#include "surface/triangle_geometry.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace tissuemesh {
namespace {

/// Botsch & Kobbelt's thresholds: splitting above 4/3 h and collapsing below 4/5 h leaves edges
/// whose lengths average about h and never oscillate between a split and a collapse.
constexpr double kSplitAbove = 4.0 / 3.0;
constexpr double kCollapseBelow = 4.0 / 5.0;
/// collapse_poor removes vertices with at most this many triangles: three or four triangles
/// around a vertex of a nearly flat patch leave angles of ~90-120 degrees at it, and so small
/// ones beside it, which no move of the vertex fixes.
constexpr std::size_t kCollapsePoorValence = 4;
/// flip_all tests the two halves of its edge list on two threads from this many edges on (fewer
/// take less time than starting the threads; the 2.1K complex has ~6,600).
constexpr std::size_t kParallelFlipTestsFrom = 20000;
/// Pattern search of search_min_angle and smooth_low_quality: first step a quarter of the
/// shortest ring edge, halved five times (the last step is 1/128 of that edge).
constexpr double kSearchFirstStep = 0.25;
constexpr int kSearchLevels = 6;

/// The pattern search's first step at v: kSearchFirstStep times v's shortest edge to `nb`.
double first_search_step(const std::vector<Eigen::Vector3d>& x, int v, const std::vector<int>& nb) {
  double step = std::numeric_limits<double>::infinity();
  for (int w : nb) step = std::min(step, (x[w] - x[v]).norm());
  return step * kSearchFirstStep;
}

std::array<int, 2> undirected(int a, int b) { return {std::min(a, b), std::max(a, b)}; }

void sort_unique(std::vector<std::array<int, 2>>& edges) {
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
}

}  // namespace

template <class EdgeOperation>
std::size_t RemeshComplex::sweep_edges(EdgeOperation operation) {
  rebuild_grid();
  std::size_t n = 0;
  for (const auto& e : edges())
    if (edge_exists(e[0], e[1]) && in_focus(0.5 * (x_[e[0]] + x_[e[1]])) && operation(e[0], e[1])) ++n;
  return n;
}

bool RemeshComplex::in_focus(const Vector3d& p) const {
  if (focus_.empty()) return true;
  const double r2 = focus_radius_ * focus_radius_;
  return std::any_of(focus_.begin(), focus_.end(), [&](const Vector3d& c) { return (p - c).squaredNorm() <= r2; });
}

void RemeshComplex::focus_on_poor_triangles(double min_angle_rad, double radius) {
  focus_.clear();
  for (int t : poor_triangles(min_angle_rad)) focus_.push_back((x_[tri_[t][0]] + x_[tri_[t][1]] + x_[tri_[t][2]]) / 3.0);
  focus_radius_ = radius;
}

template <class Bad>
std::vector<int> RemeshComplex::triangles_where(Bad bad) const {
  std::vector<int> out;
  for (std::size_t t = 0; t < tri_.size(); ++t)
    if (tri_alive_[t] && bad(x_[tri_[t][0]], x_[tri_[t][1]], x_[tri_[t][2]])) out.push_back(static_cast<int>(t));
  return out;
}

std::vector<char> RemeshComplex::vertices_of(const std::vector<int>& triangles) const {
  std::vector<char> marked(x_.size(), 0);
  for (int t : triangles)
    for (int v : tri_[t]) marked[v] = 1;
  return marked;
}

std::size_t RemeshComplex::split_long() {
  return sweep_edges([this](int a, int b) { return relative_length(a, b) > kSplitAbove && split(a, b); });
}

int RemeshComplex::collapse_edge(int a, int b, int side) {
  // A collapse of a junction edge rewrites the junction bookkeeping, shared by the whole complex.
  if (side >= 0 && (kind_[a] != Kind::Surface && kind_[b] != Kind::Surface)) return -1;
  if (!edge_exists(a, b) || !in_focus(0.5 * (x_[a] + x_[b]))) return 0;
  if (side >= 0 && !(vertex_on_side(a, side) && vertex_on_side(b, side))) return -1;
  // Here, when the try would come (not earlier: the band may still change the rings before).
  if (tracking_rings_ && !ring_changed(a) && !ring_changed(b)) {  // collapse_until_stable
    ++scratch().skipped;
    return 0;
  }
  return relative_length(a, b) < kCollapseBelow && collapse_either(a, b, kSplitAbove);
}

std::size_t RemeshComplex::flip_all(bool skip_refused) {
  rebuild_grid();
  const std::vector<std::array<int, 2>> list = edges();
  // First, on two threads and only reading: every edge's local tests (flip_passes_local_tests)
  // on the complex as the sweep finds it. Then in index order, as sweep_edges visits: an edge the
  // local tests refused is refused again while no flip has changed the triangle list of a vertex
  // they read (a flip changes those of its four vertices), so only the others are tried. The
  // flips are those of trying every edge in order; most edges are refused.
  std::vector<FlipQuad> quad(list.size());
  std::vector<char> passes(list.size(), 0);
  auto test = [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) {
      const int a = list[i][0], b = list[i][1];
      passes[i] = in_focus(0.5 * (x_[a] + x_[b])) && flip_passes_local_tests(a, b, quad[i]);
    }
  };
  if (!skip_refused)
    std::fill(passes.begin(), passes.end(), 1);
  else if (list.size() < kParallelFlipTestsFrom)
    test(0, list.size());
  else
    run_at_once([&] { test(0, list.size() / 2); }, [&] { test(list.size() / 2, list.size()); }, threads_);
  std::vector<char> touched(x_.size(), 0);
  auto touched_vertex = [&](int v) { return v >= 0 && touched[v]; };
  std::size_t n = 0;
  for (std::size_t i = 0; i < list.size(); ++i) {
    const int a = list[i][0], b = list[i][1];
    const FlipQuad& q = quad[i];
    if (!passes[i] && !touched_vertex(a) && !touched_vertex(b) && !touched_vertex(q.c) && !touched_vertex(q.d)) continue;
    FlipQuad flipped;
    if (edge_exists(a, b) && in_focus(0.5 * (x_[a] + x_[b])) && try_flip(a, b, &flipped)) {
      for (int v : {flipped.a, flipped.b, flipped.c, flipped.d}) touched[v] = 1;
      ++n;
    }
  }
  return n;
}

std::size_t RemeshComplex::flip_around(const std::vector<int>& vertices) {
  std::vector<std::array<int, 2>> candidates;
  for (int v : vertices)
    for (int t : vt_[v])
      for (int i = 0; i < 3; ++i) candidates.push_back(undirected(tri_[t][i], tri_[t][(i + 1) % 3]));
  sort_unique(candidates);
  std::size_t n = 0;
  for (const auto& e : candidates)
    if (edge_exists(e[0], e[1]) && try_flip(e[0], e[1])) ++n;
  return n;
}

std::size_t RemeshComplex::split_poor(double min_angle_rad, std::vector<int>& added) {
  rebuild_grid();
  std::vector<std::array<int, 2>> longest;
  for (int t : poor_triangles(min_angle_rad)) {
    const auto& q = tri_[t];
    const int i = extreme_edge(q, true);
    longest.push_back(undirected(q[i], q[(i + 1) % 3]));
  }
  sort_unique(longest);
  std::size_t n = 0;
  std::vector<int> ts;
  for (const auto& [a, b] : longest) {
    if (!edge_exists(a, b)) continue;
    edge_triangles(a, b, ts);
    // The smallest angle of the edge's triangles before and after the split.
    Vector3d m;
    if (!split_point(a, b, ts, m)) continue;
    double before = INFINITY, after = INFINITY;
    for (int t : ts) {
      int o = 0;
      while (tri_[t][o] == a || tri_[t][o] == b) ++o;
      const Vector3d& p = x_[tri_[t][o]];
      before = std::min(before, min_angle(x_[a], x_[b], p));
      after = std::min({after, min_angle(x_[a], m, p), min_angle(m, x_[b], p)});
    }
    if (!(after > before) || !split(a, b)) continue;
    added.push_back(static_cast<int>(x_.size()) - 1);
    ++n;
  }
  return n;
}

std::size_t RemeshComplex::collapse_poor(double min_angle_rad) {
  rebuild_grid();
  const std::vector<char> marked = vertices_of(poor_triangles(min_angle_rad));
  std::size_t n = 0;
  std::vector<int> nb;
  for (int v = 0; v < static_cast<int>(marked.size()); ++v) {
    if (!marked[v] || !vertex_alive_[v] || kind_[v] != Kind::Surface || vt_[v].size() > kCollapsePoorValence) continue;
    const double before = ring_min_angle(v, x_[v]);
    if (!(before < min_angle_rad)) continue;  // an earlier removal next to it fixed it
    // The neighbour to collapse into: the one whose remaining triangles have the largest
    // smallest angle, if that beats the one v's triangles have now.
    neighbours(v, nb);
    int best = -1;
    double best_after = before;
    for (int w : nb) {
      double after = INFINITY;
      for (int t : vt_[v]) {
        if (has(t, w)) continue;
        const NewTriangle q = moved_triangle(t, v, x_[w], w);
        after = std::min(after, min_angle(q.p[0], q.p[1], q.p[2]));
      }
      if (after > best_after) {
        best_after = after;
        best = w;
      }
    }
    // No bound on the edges left: they are edges of v's ring (and one diagonal for four
    // triangles), and the angle test above already bounds their shape.
    if (best >= 0 && try_collapse(v, best, INFINITY)) ++n;
  }
  return n;
}

int RemeshComplex::relax_vertex(int v, int side) {
  if (!vertex_alive_[v] || kind_[v] == Kind::Corner || !in_focus(x_[v])) return 0;
  if (side >= 0 && !vertex_on_side(v, side)) return -1;
  Vector3d target;
  if (kind_[v] == Kind::Surface) {
    Vector3d centroid = Vector3d::Zero();
    double weight = 0.0;
    for (int t : vt_[v]) {
      const Vector3d &a = x_[tri_[t][0]], &b = x_[tri_[t][1]], &c = x_[tri_[t][2]];
      const Vector3d g = (a + b + c) / 3.0;
      const double st = s(g), w = area_vector(a, b, c).norm() / (st * st);
      centroid += w * g;
      weight += w;
    }
    if (!(weight > 0.0) || !tangential_target(v, centroid / weight, target)) return 0;
  } else {
    std::vector<int> nb;
    neighbours(v, nb);
    Vector3d sum = Vector3d::Zero();
    double weight = 0.0;
    int found = 0;
    for (int w : nb) {
      if (curve_of_edge(v, w) != owner_[v]) continue;
      const Vector3d mid = 0.5 * (x_[v] + x_[w]);
      const double st = s(mid), wt = (x_[w] - x_[v]).norm() / (st * st);
      sum += wt * (0.5 * (mid + x_[v]));  // centroid of the half-segment towards w
      weight += wt;
      ++found;
    }
    if (found != 2 || !(weight > 0.0)) return 0;
    target = proj_.onto_curve(owner_[v], sum / weight);
    if (shorter_curve_edge(v, target) < shorter_curve_edge(v, x_[v])) return 0;
  }
  if (side >= 0 && !point_on_side(target, side)) return -1;
  return try_move(v, target);
}

void RemeshComplex::smooth_poor(double min_angle_rad, std::vector<int>& moved_vertices) {
  rebuild_grid();
  const std::vector<char> todo = vertices_of(poor_triangles(min_angle_rad));
  std::vector<int> nb;
  for (int v = 0; v < static_cast<int>(x_.size()); ++v) {
    if (!todo[v] || !vertex_alive_[v] || kind_[v] == Kind::Corner) continue;
    neighbours(v, nb);
    Vector3d target;
    if (kind_[v] == Kind::Surface) {
      Vector3d c = Vector3d::Zero();
      for (int w : nb) c += x_[w];
      if (!tangential_target(v, c / static_cast<double>(nb.size()), target)) continue;
    } else {
      Vector3d sum = Vector3d::Zero();
      int found = 0;
      for (int w : nb)
        if (curve_of_edge(v, w) == owner_[v]) {
          sum += x_[w];
          ++found;
        }
      if (found != 2) continue;
      target = proj_.onto_curve(owner_[v], 0.5 * sum);
    }
    // The full move, else halfway, else a quarter: the first that raises the smallest angle.
    const double before = ring_min_angle(v, x_[v]);
    bool done = false;
    for (double f : {1.0, 0.5, 0.25}) {
      Vector3d p = x_[v] + f * (target - x_[v]);
      if (f != 1.0) p = kind_[v] == Kind::Surface ? proj_.onto_patch(owner_[v], p) : proj_.onto_curve(owner_[v], p);
      if (kind_[v] != Kind::Surface && shorter_curve_edge(v, p) < shorter_curve_edge(v, x_[v])) continue;
      if (ring_min_angle(v, p) > before && try_move(v, p, true)) {
        done = true;
        break;
      }
    }
    if (!done) done = search_min_angle(v, nb);
    if (done) moved_vertices.push_back(v);
  }
}

template <class Score>
bool RemeshComplex::search_on_patch(int v, double step, Score score, Vector3d& best, double& best_score) const {
  best = x_[v];
  best_score = score(best);
  const Vector3d n = vertex_normal(v);
  if (n.isZero()) return false;
  const Vector3d t1 = n.unitOrthogonal(), t2 = n.cross(t1);
  for (int level = 0; level < kSearchLevels; ++level, step *= 0.5) {
    // Eight directions in the tangent plane; the landing point is projected onto v's patch.
    for (int k = 0; k < 8; ++k) {
      const double a = k * M_PI / 4.0;
      Vector3d p;
      if (!tangential_target(v, n, best + step * (std::cos(a) * t1 + std::sin(a) * t2), p)) continue;
      const double value = score(p);
      if (value > best_score) best = p, best_score = value;
    }
  }
  return true;
}

bool RemeshComplex::search_min_angle(int v, const std::vector<int>& nb) {
  double step = first_search_step(x_, v, nb);
  Vector3d best = x_[v];
  double best_angle = ring_min_angle(v, best);
  const double before = best_angle;
  if (kind_[v] == Kind::Curve) {
    // Along the junction: steps towards either curve neighbour, projected onto the junction.
    // v's shorter curve edge may shorten only while it stays above the collapse threshold
    // (4/5 h): curve vertices never move closer together than that, so a short junction loop
    // cannot shrink. Without these moves a surface's smallest angle can sit at a curve vertex,
    // where no other move changes it.
    const double shorter = shorter_curve_edge(v, x_[v]);
    for (int level = 0; level < kSearchLevels; ++level, step *= 0.5)
      for (int w : nb) {
        if (curve_of_edge(v, w) != owner_[v]) continue;
        const Vector3d p = proj_.onto_curve(owner_[v], best + step * (x_[w] - best).normalized());
        if (shorter_curve_edge(v, p) < std::min(shorter, kCollapseBelow * h(p))) continue;
        const double angle = ring_min_angle(v, p);
        if (angle > best_angle) best = p, best_angle = angle;
      }
    return best_angle > before && try_move(v, best, true);
  }
  if (!search_on_patch(v, step, [&](const Vector3d& p) { return ring_min_angle(v, p); }, best, best_angle))
    return false;
  return best_angle > before && try_move(v, best, true);
}

template <class Objective>
void RemeshComplex::search_low_quality_vertices(double q_below, double min_angle_rad, Objective objective,
                                                std::vector<int>& moved_vertices) {
  rebuild_grid();
  const std::vector<char> todo = vertices_of(triangles_where(
      [&](const Vector3d& a, const Vector3d& b, const Vector3d& c) { return triangle_quality(a, b, c) < q_below; }));
  std::vector<int> nb;
  for (int v = 0; v < static_cast<int>(x_.size()); ++v) {
    if (!todo[v] || !vertex_alive_[v] || kind_[v] != Kind::Surface) continue;
    neighbours(v, nb);
    const RingShape now = ring_shape(v, x_[v], min_angle_rad);
    auto score = [&](const Vector3d& p) { return objective(now, ring_shape(v, p, min_angle_rad)); };
    Vector3d best;
    double best_score;
    if (search_on_patch(v, first_search_step(x_, v, nb), score, best, best_score) &&
        best_score > objective(now, now) && try_move(v, best, true))
      moved_vertices.push_back(v);
  }
}

void RemeshComplex::smooth_low_quality(double q_below, double min_angle_rad, std::vector<int>& moved_vertices) {
  search_low_quality_vertices(
      q_below, min_angle_rad,
      [&](const RingShape& now, const RingShape& there) {
        return there.min_angle >= std::min(now.min_angle, min_angle_rad) && there.poor_angles <= now.poor_angles
                   ? there.min_quality
                   : -1.0;  // below any quality: never chosen
      },
      moved_vertices);
}

void RemeshComplex::smooth_mean_quality(double q_below, double min_angle_rad, double angle_floor_rad, double q_floor,
                                        std::vector<int>& moved_vertices) {
  search_low_quality_vertices(
      q_below, min_angle_rad,
      [&](const RingShape& now, const RingShape& there) {
        return there.min_angle >= std::min(now.min_angle, angle_floor_rad) && there.poor_angles <= now.poor_angles &&
                       there.min_quality >= std::min(now.min_quality, q_floor)
                   ? there.quality_sum
                   : -1.0;  // below any sum: never chosen
      },
      moved_vertices);
}

std::size_t RemeshComplex::cap_poor_triangles(double min_angle_rad) {
  const std::vector<int> poor = poor_triangles(min_angle_rad);
  for (int t : poor) {
    const auto& q = tri_[t];
    const int i = extreme_edge(q, false);
    const Vector3d &a = x_[q[i]], &b = x_[q[(i + 1) % 3]];
    cap_.add(0.5 * (a + b), (a - b).norm(), 2.0 * L);
  }
  return poor.size();
}

std::vector<int> RemeshComplex::poor_triangles(double min_angle_rad) const {
  return triangles_where(
      [&](const Vector3d& a, const Vector3d& b, const Vector3d& c) { return min_angle(a, b, c) < min_angle_rad; });
}

int RemeshComplex::extreme_edge(const std::array<int, 3>& q, bool longest) const {
  auto length2 = [&](int i) { return (x_[q[(i + 1) % 3]] - x_[q[i]]).squaredNorm(); };
  int best = 0;
  for (int i = 1; i < 3; ++i)
    if (longest ? length2(i) > length2(best) : length2(i) < length2(best)) best = i;
  return best;
}

void RemeshComplex::grade_stuck_edges(double below) {
  for (const auto& e : edges()) {
    if (kind_[e[0]] == Kind::Surface || kind_[e[1]] == Kind::Surface) continue;
    const Vector3d m = 0.5 * (x_[e[0]] + x_[e[1]]);
    const double length = (x_[e[0]] - x_[e[1]]).norm();
    if (length < below * h(m)) {
      // Reach up to twice L: the budget rescaling may still grow L.
      cap_.add(m, length, 2.0 * L);
    }
  }
}

bool RemeshComplex::match_count(std::size_t target) {
  for (int round = 0; round < 20 && alive_vertices_ != target; ++round) {
    std::vector<std::pair<double, std::array<int, 2>>> ranked;
    for (const auto& e : edges()) ranked.push_back({relative_length(e[0], e[1]), e});
    const bool remove = alive_vertices_ > target;
    if (remove)
      std::sort(ranked.begin(), ranked.end());
    else
      std::sort(ranked.begin(), ranked.end(), [](const auto& p, const auto& q) { return p.first > q.first || (p.first == q.first && p.second < q.second); });
    const std::size_t before = alive_vertices_;
    rebuild_grid();
    std::vector<char> touched(x_.size(), 0);  // edges ranked before this round's splits
    for (const auto& r : ranked) {
      if (alive_vertices_ == target) break;
      const int a = r.second[0], b = r.second[1];
      if (touched[a] || touched[b] || !edge_exists(a, b)) continue;
      if (remove ? collapse_either(a, b, 2.0 * kSplitAbove) : split(a, b)) touched[a] = touched[b] = 1;
    }
    if (alive_vertices_ == before) slack_ *= kDeviationLoosening;  // every candidate refused: loosen the bound
  }
  slack_ = 1.0;
  return alive_vertices_ == target;
}

}  // namespace tissuemesh
