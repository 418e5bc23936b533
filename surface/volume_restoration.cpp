// Why least-norm over patches rather than per tissue: an interface belongs to two tissues, and a
// move of one side is a move of the other; solving for the patches lets a fgt deficit be paid by
// the fat around it (whose relative change is small) without a second, contradicting move.
#include "surface/volume_restoration.h"

#include "core/errors.h"
#include "core/union_find.h"
#include "surface/surface_checks.h"

#include <Eigen/Dense>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <utility>

namespace tissuemesh {

namespace {

using Eigen::Vector3d;

constexpr double kMaxNormalTurnDeg = 60.0;
constexpr int kTaperRings = 3;
constexpr double kFlatDeg = 10.0;   // faces within this of the vertex normal: full offset
constexpr double kBentDeg = 60.0;   // a face this far off: none
constexpr double kBentIslandDeg = 80.0;  // the same on a component without junctions (no rim to stretch)
constexpr int kFreezings = 8;       // a round that breaks the surface is solved again without the spot this often
constexpr int kHalvings = 3;        // and then retried at half its offsets this often

constexpr double kFrozenMarginDeg = 2.0;  // triangles this close to the smallest angle stay
constexpr double kMaxMoveOfEdge = 1.0;    // largest move of a vertex a round, in its shortest edges
constexpr double kErrorSlack = 1e-3;      // a round may raise one tissue's relative error this much,
constexpr double kErrorSlackOfSum = 0.05; // plus this part of the sum of the errors it corrects
constexpr double kReleaseMinError = 0.01; // a tissue this far off that a round cannot move
constexpr double kStuckGain = 0.1;        // (whose error falls by less than this part of itself) is released

double triangle_min_angle_deg(const TriSurface& s, const std::array<int, 3>& w) {
  double smallest = 180.0;
  for (int e = 0; e < 3; ++e) {
    const Vector3d a = s.points[w[(e + 1) % 3]] - s.points[w[e]], b = s.points[w[(e + 2) % 3]] - s.points[w[e]];
    smallest = std::min(smallest, std::atan2(a.cross(b).norm(), a.dot(b)) * 180.0 / M_PI);
  }
  return smallest;
}

double min_triangle_angle_deg(const TriSurface& s) {
  double smallest = 180.0;
  for (const auto& w : s.triangles) smallest = std::min(smallest, triangle_min_angle_deg(s, w));
  return smallest;
}

Vector3d raw_normal(const TriSurface& s, int t) {
  const auto& w = s.triangles[t];
  return (s.points[w[1]] - s.points[w[0]]).cross(s.points[w[2]] - s.points[w[0]]);
}

}  // namespace

std::map<int, double> enclosed_volumes(const TriSurface& s) {
  std::map<int, double> v;
  for (int id = 1; id <= static_cast<int>(s.tissue_names.size()); ++id) v[id] = 0.0;
  for (std::size_t t = 0; t < s.triangles.size(); ++t) {
    const auto& w = s.triangles[t];
    // The normal points from p into q: the triangle bounds p outward and q inward.
    const double six_v = s.points[w[0]].dot(s.points[w[1]].cross(s.points[w[2]]));
    if (s.labels[t][0] > 0) v[s.labels[t][0]] += six_v / 6.0;
    if (s.labels[t][1] > 0) v[s.labels[t][1]] -= six_v / 6.0;
  }
  return v;
}

VolumeRestoration restore_volumes(TriSurface& s, const std::map<int, double>& reference, double tolerance_rel,
                                  int max_rounds, const RestorationCheck& check, double max_total_move_mm) {
  const int n_tissues = static_cast<int>(s.tissue_names.size());
  for (const auto& [id, v] : reference)
    if (id < 1 || id > n_tissues || !(v > 0.0 && std::isfinite(v)))
      throw InputError("volume restoration: reference volume of tissue id " + std::to_string(id) +
                       " is not a positive volume of a tissue of the surface");
  if (!(max_total_move_mm > 0.0))
    throw InputError("volume restoration: the bound on a vertex's moves must be > 0 mm");
  VolumeRestoration result;
  result.volume_before_mm3 = enclosed_volumes(s);
  result.volume_after_mm3 = result.volume_before_mm3;

  // Patches (region pairs) and, per vertex, the one patch it lies on (-1: on several, a junction).
  std::map<std::pair<int, int>, int> patch_of_pair;
  std::vector<int> patch(s.triangles.size());
  std::vector<std::pair<int, int>> pairs;
  for (std::size_t t = 0; t < s.triangles.size(); ++t) {
    const std::pair<int, int> key{s.labels[t][0], s.labels[t][1]};
    const auto [it, added] = patch_of_pair.emplace(key, static_cast<int>(pairs.size()));
    if (added) pairs.push_back(key);
    patch[t] = it->second;
  }
  std::vector<int> vertex_patch(s.points.size(), -2);  // -2: on no triangle
  for (std::size_t t = 0; t < s.triangles.size(); ++t)
    for (int v : s.triangles[t]) vertex_patch[v] = vertex_patch[v] == -2 || vertex_patch[v] == patch[t] ? patch[t] : -1;
  for (const auto& line : s.junctions)
    for (int v : line) vertex_patch[v] = -1;
  // Weights: 0 on the junctions, growing over kTaperRings rings of edges to 1, so that the
  // triangles at a junction (often the smallest and most folded) tilt by a fraction of the offset.
  std::vector<std::vector<int>> neighbours(s.points.size());
  for (const auto& t : s.triangles)
    for (int e = 0; e < 3; ++e) neighbours[t[e]].push_back(t[(e + 1) % 3]), neighbours[t[(e + 1) % 3]].push_back(t[e]);
  // A vertex moves by at most kMaxMoveOfEdge of its shortest edge a round: where few vertices of a
  // patch may move (a small island, a thin tube most of whose vertices are bent), the solved
  // offset is large, and those vertices would make spikes. Their move is clipped there, and the
  // next round, which measures the volumes again, goes on from where they got. (Holding them and
  // solving again instead raised the offset of the rest, which were held in turn: on a map of
  // thin vessels every vessel vertex ended up held.)
  std::vector<double> max_move(s.points.size(), 0.0);
  for (std::size_t v = 0; v < s.points.size(); ++v) {
    double shortest = std::numeric_limits<double>::infinity();
    for (int w : neighbours[v]) shortest = std::min(shortest, (s.points[w] - s.points[v]).norm());
    if (std::isfinite(shortest)) max_move[v] = kMaxMoveOfEdge * shortest;
  }
  // What is left of each vertex's bound on the sum of its moves.
  std::vector<double> move_left(s.points.size(), max_total_move_mm);
  std::vector<double> weight(s.points.size(), 0.0);
  {
    std::vector<int> ring(s.points.size(), kTaperRings);
    std::vector<int> front;
    for (std::size_t v = 0; v < s.points.size(); ++v)
      if (vertex_patch[v] == -1) {
        ring[v] = 0;
        front.push_back(static_cast<int>(v));
      }
    for (int r = 1; r < kTaperRings && !front.empty(); ++r) {
      std::vector<int> next;
      for (int v : front)
        for (int w : neighbours[v])
          if (ring[w] > r) {
            ring[w] = r;
            next.push_back(w);
          }
      front = std::move(next);
    }
    for (std::size_t v = 0; v < s.points.size(); ++v)
      weight[v] = vertex_patch[v] >= 0 ? static_cast<double>(ring[v]) / kTaperRings : 0.0;
  }
  // And 0 where the patch bends sharply at the vertex (the rim of a thin sheet): an offset along
  // diverging normals stretches those triangles; flat and gently curved parts move instead.
  {
    std::vector<Vector3d> n(s.points.size(), Vector3d::Zero());
    for (std::size_t t = 0; t < s.triangles.size(); ++t)
      for (int v : s.triangles[t]) n[v] += raw_normal(s, static_cast<int>(t));
    std::vector<double> spread(s.points.size(), 1.0);  // smallest cosine between a face and the vertex normal
    for (std::size_t t = 0; t < s.triangles.size(); ++t) {
      const Vector3d f = raw_normal(s, static_cast<int>(t)).normalized();
      for (int v : s.triangles[t]) spread[v] = std::min(spread[v], f.dot(n[v].normalized()));
    }
    // A component of the surface that touches no junction (an island inside one other tissue, a
    // marker clip) is a closed surface moving as a whole: inflating it along its normals grows it
    // like a ball, so however coarse it is, it may bend much further before its vertices stay.
    std::vector<int> component = singleton_sets(s.points.size());
    for (const auto& t : s.triangles)
      for (int e = 1; e < 3; ++e) {
        const int a = find_root(component, t[0]), b = find_root(component, t[e]);
        if (a != b) component[std::max(a, b)] = std::min(a, b);
      }
    std::vector<char> has_junction(s.points.size(), 0);
    for (std::size_t v = 0; v < s.points.size(); ++v)
      if (vertex_patch[v] == -1) has_junction[find_root(component, static_cast<int>(v))] = 1;
    const double flat = std::cos(kFlatDeg * M_PI / 180.0);
    for (std::size_t v = 0; v < s.points.size(); ++v) {
      const bool island = !has_junction[find_root(component, static_cast<int>(v))];
      const double bent = std::cos((island ? kBentIslandDeg : kBentDeg) * M_PI / 180.0);
      weight[v] *= std::clamp((spread[v] - bent) / (flat - bent), 0.0, 1.0);
    }
  }
  // And 0 at the triangles within kFrozenMarginDeg of the smallest angle: those set Table 1's
  // minimum, which the restoration must not lower.
  const double min_angle_before = min_triangle_angle_deg(s);
  for (const auto& w : s.triangles)
    if (triangle_min_angle_deg(s, w) < min_angle_before + kFrozenMarginDeg)
      for (int v : w) weight[v] = 0.0;
  // Only tissues with a reference constrain the offsets, until they are released (below).
  std::vector<int> constrained;
  for (const auto& [id, v] : reference) constrained.push_back(id);
  const int np = static_cast<int>(pairs.size());
  if (np == 0 || constrained.empty()) return result;

  auto error = [&](const std::map<int, double>& volumes, int id) {
    return std::abs(volumes.at(id) / reference.at(id) - 1.0);
  };
  auto within = [&](const std::map<int, double>& volumes) {
    for (int id : constrained)
      if (error(volumes, id) > tolerance_rel) return false;
    return true;
  };
  // A vertex held in place for the remaining rounds (counted once).
  auto hold = [&](int v) {
    if (weight[v] > 0.0) ++result.frozen_vertices;
    weight[v] = 0.0;
  };
  for (int round = 0; round < max_rounds && !within(result.volume_after_mm3); ++round) {
    std::vector<Vector3d> normal(s.points.size(), Vector3d::Zero());
    for (std::size_t t = 0; t < s.triangles.size(); ++t)
      for (int v : s.triangles[t]) normal[v] += raw_normal(s, static_cast<int>(t));
    const std::vector<Vector3d> before = s.points;
    std::vector<Vector3d> triangle_normal(s.triangles.size());
    for (std::size_t t = 0; t < s.triangles.size(); ++t) triangle_normal[t] = raw_normal(s, static_cast<int>(t));
    const double min_cos = std::cos(kMaxNormalTurnDeg * M_PI / 180.0);

    // The offsets d_k of the patches for the current weights.
    auto solve = [&] {
      // Areas of the movable part of each patch: the triangles' area shared out to their movable
      // vertices (a third each), so a junction-bound strip counts for less than its full area.
      Eigen::VectorXd area = Eigen::VectorXd::Zero(np);
      for (std::size_t t = 0; t < s.triangles.size(); ++t) {
        const double a = 0.5 * triangle_normal[t].norm();
        for (int v : s.triangles[t]) area[patch[t]] += weight[v] * a / 3.0;
      }
      // C d = deficit, C(i, k) = +A_k when tissue i is p of patch k, -A_k when it is q; each row
      // divided by the tissue's reference volume, so that where held vertices leave no exact
      // solution the least-squares one weighs every tissue's relative error alike.
      const int nc = static_cast<int>(constrained.size());
      Eigen::MatrixXd C = Eigen::MatrixXd::Zero(nc, np);
      Eigen::VectorXd deficit(nc);
      for (int i = 0; i < nc; ++i) {
        const int id = constrained[i];
        const double ref = reference.at(id);
        deficit[i] = (ref - result.volume_after_mm3.at(id)) / ref;
        for (int k = 0; k < np; ++k) {
          if (pairs[k].first == id) C(i, k) = area[k] / ref;
          if (pairs[k].second == id) C(i, k) = -area[k] / ref;
        }
      }
      // Least norm in sum A_k d_k^2: d = W^-1 C^T (C W^-1 C^T)^+ deficit, W = diag(A).
      Eigen::VectorXd inv_area(np);
      for (int k = 0; k < np; ++k) inv_area[k] = area[k] > 0.0 ? 1.0 / area[k] : 0.0;
      const Eigen::MatrixXd CWinv = C * inv_area.asDiagonal();
      const Eigen::MatrixXd M = CWinv * C.transpose();
      const Eigen::VectorXd lambda = M.completeOrthogonalDecomposition().solve(deficit);
      return Eigen::VectorXd(CWinv.transpose() * lambda);
    };
    // Moves each movable vertex by scale * d of its patch along its area-weighted normal there;
    // true if no triangle turns over, the smallest angle stays and the surface stays valid (or
    // `check` accepts it), else `bad` lists the triangles that broke one of these and
    // `bad_vertices` the vertices `check` faults.
    double largest = 0.0;
    std::vector<int> bad_vertices;  // at fault by `check`
    auto attempt = [&](const Eigen::VectorXd& d, double scale, std::vector<int>& bad) {
      s.points = before;
      largest = 0.0;
      for (std::size_t v = 0; v < s.points.size(); ++v) {
        if (weight[v] == 0.0 || normal[v].squaredNorm() == 0.0) continue;
        const double cap = std::min(max_move[v], move_left[v]);
        const double move = std::clamp(scale * weight[v] * d[vertex_patch[v]], -cap, cap);
        s.points[v] += move * normal[v].normalized();
        largest = std::max(largest, std::abs(move));
      }
      bad.clear();
      for (std::size_t t = 0; t < s.triangles.size(); ++t) {
        const Vector3d n = raw_normal(s, static_cast<int>(t));
        if (!(n.dot(triangle_normal[t]) > min_cos * n.norm() * triangle_normal[t].norm()) ||
            triangle_min_angle_deg(s, s.triangles[t]) < min_angle_before)
          bad.push_back(static_cast<int>(t));
      }
      bad_vertices.clear();
      bool valid = true;
      if (check) {
        valid = check(s, bad_vertices);
      } else {
        std::vector<int> intersecting;
        valid = check_surface(s, &intersecting, PairSearch::Grid).valid();
        bad.insert(bad.end(), intersecting.begin(), intersecting.end());
      }
      return valid && bad.empty() && bad_vertices.empty();
    };
    // Where a round breaks the surface (a thin gap closing, a fold turning over), the vertices of
    // those triangles and their neighbours stop moving and the offsets are solved again, so that
    // one tight spot among thousands of islands does not hold every patch back; after
    // kFreezings of these, the round is retried at half its offsets, then undone. One try of the
    // round: true when kept.
    std::map<int, double> volumes;
    bool release = false;  // a tissue was released: solve the round again
    auto try_round = [&] {
      std::vector<int> bad;
      bool ok = false;
      Eigen::VectorXd d = solve();
      for (int freezing = 0; !ok; ++freezing) {
        ok = attempt(d, 1.0, bad);
        if (ok || freezing == kFreezings || (bad.empty() && bad_vertices.empty())) break;
        for (int t : bad) bad_vertices.insert(bad_vertices.end(), s.triangles[t].begin(), s.triangles[t].end());
        for (int v : bad_vertices) {
          hold(v);
          for (int w : neighbours[v]) hold(w);
        }
        d = solve();
      }
      double scale = 0.5;
      for (int halving = 0; halving < kHalvings && !ok; ++halving, scale *= 0.5) ok = attempt(d, scale, bad);
      // A round must also bring the tissues closer to their references (with vertices held, the
      // offsets are a least-squares compromise that could trade one tissue for another): the sum of
      // the relative errors falls, and no tissue's grows by more than kErrorSlack plus a small part
      // of that sum (a large step is not linear: a growing ball takes more than its first-order
      // volume from its neighbour).
      // A tissue that this round could not move towards its reference although it is far off (a
      // tube whose every vertex bends, a blob whose vertices are held, an element across) would
      // otherwise hold the others back: its large relative deficit dominates the least-squares
      // offsets, which then trade the other tissues' small ones for nothing. Of those, the one
      // furthest off is released (it no longer constrains the offsets, and its vertices stay where
      // they are, so that its neighbours do not take its volume) and the round is solved again; a
      // tissue within kReleaseMinError is never released.
      volumes.clear();
      if (ok) {
        volumes = enclosed_volumes(s);
        double sum_before = 0.0, sum_after = 0.0;
        for (int id : constrained) sum_before += error(result.volume_after_mm3, id);
        bool better = true;
        for (int id : constrained) {
          const double e0 = error(result.volume_after_mm3, id), e1 = error(volumes, id);
          sum_after += e1;
          better = better && e1 <= e0 + kErrorSlack + kErrorSlackOfSum * sum_before;
        }
        if (better && sum_after < sum_before) return true;
        int stuck = -1;
        for (int id : constrained) {
          const double e0 = error(result.volume_after_mm3, id);
          if (e0 >= kReleaseMinError && error(volumes, id) > (1.0 - kStuckGain) * e0 &&
              (stuck < 0 || e0 > error(result.volume_after_mm3, stuck)))
            stuck = id;
        }
        if (stuck >= 0 && constrained.size() > 1) {
          constrained.erase(std::find(constrained.begin(), constrained.end(), stuck));
          result.released.push_back(stuck);
          for (std::size_t t = 0; t < s.triangles.size(); ++t)
            if (s.labels[t][0] == stuck || s.labels[t][1] == stuck)
              for (int v : s.triangles[t]) weight[v] = 0.0;
          release = true;
        }
      }
      return false;
    };
    bool kept = false;
    do {
      release = false;
      kept = try_round();
      if (!kept) s.points = before;
    } while (!kept && release);
    if (!kept) {
      result.stopped_early = true;
      break;
    }
    // Not below 0: a move clipped at the bound can measure a rounding error longer than it.
    for (std::size_t v = 0; v < s.points.size(); ++v)
      move_left[v] = std::max(0.0, move_left[v] - (s.points[v] - before[v]).norm());
    ++result.rounds;
    result.max_offset_mm = std::max(result.max_offset_mm, largest);
    result.volume_after_mm3 = volumes;
  }
  return result;
}

}  // namespace tissuemesh
