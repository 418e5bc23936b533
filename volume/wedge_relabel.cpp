#include "volume/wedge_relabel.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace tissuemesh {

namespace {

constexpr std::size_t kMaxStar = 1024;

class Neighbourhood {
 public:
  Neighbourhood(const TetMesh& mesh, int t, const AcrossFace& across) : m_(mesh), t_(t), across_(across) {}

  // Tets containing node v reached from t through faces that contain v (empty beyond kMaxStar).
  std::vector<int> star(int v) const {
    std::vector<int> found = {t_};
    for (std::size_t i = 0; i < found.size(); ++i) {
      if (found.size() > kMaxStar) return {};
      const auto& X = m_.tets[found[i]];
      for (int f = 0; f < 4; ++f) {
        if (X[f] == v) continue;  // the face opposite v does not contain it
        const int nb = across_(X[(f + 1) % 4], X[(f + 2) % 4], X[(f + 3) % 4], found[i]);
        if (nb >= 0 && std::find(found.begin(), found.end(), nb) == found.end()) found.push_back(nb);
      }
    }
    return found;
  }

  // Face-connected groups (through faces containing v) of the tets of `tissue` among `around`,
  // with t taken to be of tissue t_as.
  int star_groups(const std::vector<int>& around, int v, int tissue, int t_as) const {
    std::vector<int> seen, stack;
    int groups = 0;
    for (int start : around) {
      if (of(start, t_as) != tissue || std::find(seen.begin(), seen.end(), start) != seen.end()) continue;
      ++groups;
      seen.push_back(start);
      stack = {start};
      while (!stack.empty()) {
        const int x = stack.back();
        stack.pop_back();
        const auto& X = m_.tets[x];
        for (int f = 0; f < 4; ++f) {
          if (X[f] == v) continue;
          const int nb = across_(X[(f + 1) % 4], X[(f + 2) % 4], X[(f + 3) % 4], x);
          if (nb < 0 || of(nb, t_as) != tissue || std::find(seen.begin(), seen.end(), nb) != seen.end()) continue;
          seen.push_back(nb);
          stack.push_back(nb);
        }
      }
    }
    return groups;
  }

  // The tets around edge (r, s) in order, starting at t; `closed` when they go all the way round
  // (an edge on the outer boundary has an open fan).
  std::vector<int> edge_fan(int r, int s, bool& closed) const {
    int third[2], n = 0;
    for (int x : m_.tets[t_])
      if (x != r && x != s) third[n++] = x;
    std::vector<int> sides[2];
    closed = false;
    for (int side = 0; side < 2 && !closed; ++side) {
      int cur = t_, apex = third[side];
      for (std::size_t step = 0; step < kMaxStar; ++step) {
        const int nb = across_(r, s, apex, cur);
        if (nb < 0) break;
        if (nb == t_) {
          closed = true;
          break;
        }
        sides[side].push_back(nb);
        int w = -1;
        for (int x : m_.tets[nb])
          if (x != r && x != s && x != apex) w = x;
        cur = nb;
        apex = w;
      }
    }
    std::vector<int> fan;
    if (!closed) fan.assign(sides[1].rbegin(), sides[1].rend());
    fan.push_back(t_);
    fan.insert(fan.end(), sides[0].begin(), sides[0].end());
    return fan;
  }

  // Runs of consecutive tets of `tissue` in a fan (cyclic when closed), t taken as tissue t_as.
  int fan_runs(const std::vector<int>& fan, bool closed, int tissue, int t_as) const {
    auto is = [&](std::size_t i) { return of(fan[i], t_as) == tissue; };
    int runs = 0;
    for (std::size_t i = 0; i < fan.size(); ++i) {
      const bool prev = i > 0 ? is(i - 1) : (closed && is(fan.size() - 1));
      if (is(i) && !prev) ++runs;
    }
    if (closed && runs == 0 && is(0)) runs = 1;  // all the way round
    return runs;
  }

 private:
  int of(int x, int t_as) const { return x == t_ ? t_as : m_.tissue_ids[x]; }

  const TetMesh& m_;
  int t_;
  const AcrossFace& across_;
};

}  // namespace

bool is_flat_wedge(const TetMesh& mesh, int t) {
  const auto& T = mesh.tets[t];
  double longest = 0;
  for (int i = 0; i < 4; ++i)
    for (int j = i + 1; j < 4; ++j) longest = std::max(longest, (mesh.points[T[i]] - mesh.points[T[j]]).norm());
  const double v = std::abs(signed_tet_volume(mesh.points[T[0]], mesh.points[T[1]], mesh.points[T[2]], mesh.points[T[3]]));
  return v <= kFlatWedgeFraction * longest * longest * longest / (6.0 * std::sqrt(2.0));
}

bool relabel_keeps_topology(const TetMesh& mesh, int t, int to, const AcrossFace& across) {
  const int from = mesh.tissue_ids[t];
  if (to == from) return true;
  // The wedge's tissue may lose a group (the wedge was a group of its own there: a pinch goes)
  // but never gain one (the wedge joined two groups); the receiving tissue keeps its groups or
  // newly reaches a node or edge through the wedge, but is never joined or pinched by it.
  auto acceptable = [&](int tissue, int before, int after) {
    if (tissue == from) return after <= before;
    return after == before || (before == 0 && after == 1);
  };
  const Neighbourhood around_t(mesh, t, across);
  const auto& T = mesh.tets[t];
  for (int v : T) {
    const std::vector<int> star = around_t.star(v);
    if (star.empty()) return false;
    for (int tissue : {from, to})
      if (!acceptable(tissue, around_t.star_groups(star, v, tissue, from), around_t.star_groups(star, v, tissue, to)))
        return false;
  }
  for (int i = 0; i < 4; ++i)
    for (int j = i + 1; j < 4; ++j) {
      bool closed = false;
      const std::vector<int> fan = around_t.edge_fan(T[i], T[j], closed);
      for (int tissue : {from, to})
        if (!acceptable(tissue, around_t.fan_runs(fan, closed, tissue, from), around_t.fan_runs(fan, closed, tissue, to)))
          return false;
    }
  return true;
}

}  // namespace tissuemesh
