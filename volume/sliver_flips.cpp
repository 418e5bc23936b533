#include "volume/sliver_flips.h"

#include "core/face_key.h"
#include "volume/wedge_relabel.h"
#include "quality/mesh_quality.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <unordered_map>
#include <vector>

namespace tissuemesh {

namespace {

constexpr int kMaxRing = 7;  // edge removal beyond 7 tets rarely helps and grows as n^3

struct NewTet {
  std::array<int, 4> v;
  double quality;
};

class FlipMesh {
 public:
  explicit FlipMesh(TetMesh& m) : m_(m), alive_(m.tets.size(), 1), quality_(m.tets.size()) {
    // Each tet's quality on its own (two threads); the face map reserved for its ~2 faces per tet
    // (nothing iterates over it, so its bucket count changes no result).
    const auto n = static_cast<std::ptrdiff_t>(m.tets.size());
#pragma omp parallel for schedule(static) num_threads(2)
    for (std::ptrdiff_t t = 0; t < n; ++t)
      quality_[static_cast<std::size_t>(t)] = min_dihedral(m.tets[static_cast<std::size_t>(t)]);
    faces_.reserve(2 * m.tets.size() + m.tets.size() / 4);
    for (std::size_t t = 0; t < m.tets.size(); ++t) add_faces(static_cast<int>(t));
  }

  double min_dihedral(const std::array<int, 4>& t) const {
    return tet_volume_and_min_dihedral(m_.points[t[0]], m_.points[t[1]], m_.points[t[2]], m_.points[t[3]])
        .min_dihedral_deg;
  }
  double volume(const std::array<int, 4>& t) const {
    return signed_tet_volume(m_.points[t[0]], m_.points[t[1]], m_.points[t[2]], m_.points[t[3]]);
  }
  // A positively oriented tet on these four nodes, or nothing if it is (nearly) flat.
  bool oriented(std::array<int, 4> t, double min_volume, NewTet& out) const {
    double v = volume(t);
    if (v < 0) {
      std::swap(t[2], t[3]);
      v = -v;
    }
    if (!(v > min_volume)) return false;
    out = {t, min_dihedral(t)};
    return true;
  }

  // Other tet on face (a,b,c) than `t`, or -1.
  int across(int a, int b, int c, int t) const {
    auto it = faces_.find(key(a, b, c));
    if (it == faces_.end()) return -1;
    return it->second[0] == t ? it->second[1] : it->second[0];
  }

  // Tries the 2-3 flip through face `f` (opposite vertex index f) of tet t.
  bool try_23(int t, int f, std::vector<NewTet>& out, std::vector<int>& old) const {
    const auto& T = m_.tets[t];
    const int a = T[(f + 1) % 4], b = T[(f + 2) % 4], c = T[(f + 3) % 4], d = T[f];
    const int u = across(a, b, c, t);
    if (u < 0 || m_.tissue_ids[u] != m_.tissue_ids[t]) return false;
    const auto& U = m_.tets[u];
    int e = -1;
    for (int x : U)
      if (x != a && x != b && x != c) e = x;
    const double union_volume = volume(T) + volume(U);
    const double eps = 1e-9 * union_volume;
    std::vector<NewTet> n(3);
    if (!oriented({a, b, d, e}, eps, n[0]) || !oriented({b, c, d, e}, eps, n[1]) ||
        !oriented({c, a, d, e}, eps, n[2]))
      return false;
    double sum = 0;
    for (const auto& x : n) sum += volume(x.v);
    if (std::abs(sum - union_volume) > 1e-9 * union_volume) return false;  // d-e misses the face
    out = n;
    old = {t, u};
    return true;
  }

  // Tries removing edge (p,q) of tet t: a closed ring of tets around it, all of `tissue` except
  // possibly t itself (an interface flip relabels t) or, when `wedge` is given, one other tet of
  // the ring that is a thin wedge of another tissue on `tissue`'s interface (relabelled; its
  // index is returned in *wedge, else -1).
  bool try_edge_removal(int t, int p, int q, int tissue, std::vector<NewTet>& out, std::vector<int>& old,
                        int* wedge = nullptr) const {
    if (wedge) *wedge = -1;
    const auto& T = m_.tets[t];
    int r = -1, s = -1;
    for (int x : T)
      if (x != p && x != q) (r < 0 ? r : s) = x;
    std::vector<int> ring = {r}, tets = {t};
    int cur = t, next = s;
    while (true) {
      if (static_cast<int>(ring.size()) >= kMaxRing) return false;
      ring.push_back(next);
      const int nb = across(p, q, next, cur);
      if (nb < 0) return false;  // boundary edge
      if (m_.tissue_ids[nb] != tissue) {  // interface edge: only one thin wedge may be relabelled
        if (!wedge || *wedge >= 0 || wedge_tissue(nb, p, q) != tissue) return false;
        *wedge = nb;
      }
      int w = -1;
      for (int x : m_.tets[nb])
        if (x != p && x != q && x != next) w = x;
      if (w == r) {
        tets.push_back(nb);
        break;
      }
      tets.push_back(nb);
      cur = nb;
      next = w;
    }
    const int n = static_cast<int>(ring.size());
    if (n != static_cast<int>(tets.size()) || n < 3) return false;
    double union_volume = 0;
    for (int x : tets) union_volume += volume(m_.tets[x]);
    const double eps = 1e-9 * union_volume;
    // best[i][j]: best worst-quality of a triangulation of ring[i..j]; choice[i][j]: its apex k.
    const double none = -std::numeric_limits<double>::infinity();
    std::array<std::array<double, kMaxRing + 1>, kMaxRing + 1> best{};
    std::array<std::array<int, kMaxRing + 1>, kMaxRing + 1> choice{};
    for (int len = 1; len < n; ++len)
      for (int i = 0; i + len < n; ++i) {
        const int j = i + len;
        if (len == 1) {
          best[i][j] = std::numeric_limits<double>::infinity();
          continue;
        }
        best[i][j] = none;
        for (int k = i + 1; k < j; ++k) {
          // The triangle must separate p from q, else its two tets overlap.
          if (volume({ring[i], ring[k], ring[j], p}) * volume({ring[i], ring[k], ring[j], q}) >= 0) continue;
          NewTet tp, tq;
          if (!oriented({ring[i], ring[k], ring[j], p}, eps, tp) || !oriented({ring[i], ring[k], ring[j], q}, eps, tq))
            continue;
          const double qk = std::min({best[i][k], best[k][j], tp.quality, tq.quality});
          if (qk > best[i][j]) {
            best[i][j] = qk;
            choice[i][j] = k;
          }
        }
      }
    if (best[0][n - 1] == none) return false;
    std::vector<NewTet> result;
    std::vector<std::pair<int, int>> stack = {{0, n - 1}};
    while (!stack.empty()) {
      const auto [i, j] = stack.back();
      stack.pop_back();
      if (j - i < 2) continue;
      const int k = choice[i][j];
      NewTet tp, tq;
      oriented({ring[i], ring[k], ring[j], p}, eps, tp);
      oriented({ring[i], ring[k], ring[j], q}, eps, tq);
      result.push_back(tp);
      result.push_back(tq);
      stack.push_back({i, k});
      stack.push_back({k, j});
    }
    double sum = 0;
    for (const auto& x : result) sum += volume(x.v);
    if (std::abs(sum - union_volume) > 1e-9 * union_volume) return false;  // ring not star-shaped
    out = result;
    old = tets;
    return true;
  }

  // Tissue B of the two tets across the faces of t that contain edge (p,q), when t is a flat
  // wedge on B's interface that can be given to B without changing anything else: t is flat
  // (is_flat_wedge), and either t's other two faces border t's own tissue A and every other tet
  // around the opposite edge (r,s) is A (so A stays face-connected there), or giving t to B
  // keeps every tissue's local topology (wedge_relabel.h; e.g. a sliver of A between two
  // faces of B, one of A and one of a third tissue). -1 otherwise.
  int wedge_tissue(int t, int p, int q) const {
    int other[2], n = 0;
    for (int x : m_.tets[t])
      if (x != p && x != q) other[n++] = x;
    const int r = other[0], s = other[1], a = m_.tissue_ids[t];
    const int n1 = across(p, q, r, t), n2 = across(p, q, s, t);
    if (n1 < 0 || n2 < 0) return -1;
    const int b = m_.tissue_ids[n1];
    if (b != m_.tissue_ids[n2] || b == a) return -1;
    if (!is_flat_wedge(m_, t)) return -1;
    const int n3 = across(r, s, p, t), n4 = across(r, s, q, t);
    const bool inside_own = n3 >= 0 && n4 >= 0 && m_.tissue_ids[n3] == a && m_.tissue_ids[n4] == a &&
                            all_around_edge_are(r, s, t, a);
    if (!inside_own &&
        !relabel_keeps_topology(m_, t, b, [this](int x, int y, int z, int u) { return across(x, y, z, u); }))
      return -1;
    return b;
  }

  // True if every tet around edge (r,s) other than `t` has tissue `tissue` (walking both ways
  // from t; an edge on the boundary has an open fan).
  bool all_around_edge_are(int r, int s, int t, int tissue) const {
    int third[2], n = 0;
    for (int x : m_.tets[t])
      if (x != r && x != s) third[n++] = x;
    for (int side = 0; side < 2; ++side) {
      int cur = t, apex = third[side];
      for (int step = 0; step < 64; ++step) {
        const int nb = across(r, s, apex, cur);
        if (nb < 0 || nb == t) break;
        if (m_.tissue_ids[nb] != tissue) return false;
        int w = -1;
        for (int x : m_.tets[nb])
          if (x != r && x != s && x != apex) w = x;
        cur = nb;
        apex = w;
      }
    }
    return true;
  }

  void apply(const std::vector<int>& old, const std::vector<NewTet>& fresh, int tissue) {
    for (int t : old) {
      remove_faces(t);
      alive_[t] = 0;
    }
    for (const auto& n : fresh) {
      m_.tets.push_back(n.v);
      m_.tissue_ids.push_back(tissue);
      quality_.push_back(n.quality);
      alive_.push_back(1);
      add_faces(static_cast<int>(m_.tets.size()) - 1);
    }
  }

  // Flips keep every node in use, so only tets are dropped.
  void compact() { keep_tets(m_, alive_); }

  bool alive(int t) const { return alive_[t]; }
  double quality(int t) const { return quality_[t]; }
  int tissue(int t) const { return m_.tissue_ids[t]; }
  std::size_t size() const { return m_.tets.size(); }
  const std::array<int, 4>& tet(int t) const { return m_.tets[t]; }

 private:
  static std::uint64_t key(int a, int b, int c) { return face_key(a, b, c); }
  void add_faces(int t) {
    const auto& T = m_.tets[t];
    for (int f = 0; f < 4; ++f) {
      auto [it, fresh] = faces_.try_emplace(key(T[(f + 1) % 4], T[(f + 2) % 4], T[(f + 3) % 4]),
                                            std::array<int, 2>{t, -1});
      if (!fresh) it->second[it->second[0] < 0 ? 0 : 1] = t;
    }
  }
  void remove_faces(int t) {
    const auto& T = m_.tets[t];
    for (int f = 0; f < 4; ++f) {
      auto it = faces_.find(key(T[(f + 1) % 4], T[(f + 2) % 4], T[(f + 3) % 4]));
      if (it->second[0] == t) it->second[0] = -1;
      if (it->second[1] == t) it->second[1] = -1;
      if (it->second[0] < 0 && it->second[1] < 0) faces_.erase(it);
    }
  }

  TetMesh& m_;
  std::vector<char> alive_;
  std::vector<double> quality_;
  std::unordered_map<std::uint64_t, std::array<int, 2>> faces_;
};

}  // namespace

SliverFlipResult flip_slivers(TetMesh& mesh, double target_deg, bool allow_interface_flips, int max_passes) {
  SliverFlipResult r;
  if (mesh.points.size() >= kMaxFaceKeyNodes) return r;  // beyond the face-key range: leave as is
  FlipMesh fm(mesh);
  static const int kEdges[6][2] = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}};
  for (int pass = 0; pass < max_passes; ++pass) {
    std::vector<int> bad;
    for (std::size_t t = 0; t < fm.size(); ++t)
      if (fm.alive(static_cast<int>(t)) && fm.quality(static_cast<int>(t)) < target_deg) bad.push_back(static_cast<int>(t));
    std::sort(bad.begin(), bad.end(), [&](int a, int b) {
      return fm.quality(a) != fm.quality(b) ? fm.quality(a) < fm.quality(b) : a < b;
    });
    ++r.passes;
    std::size_t applied = 0;
    for (int t : bad) {
      if (!fm.alive(t)) continue;
      std::vector<NewTet> best_new, cand;
      std::vector<int> best_old, cand_old;
      double best_q = -1;
      int best_kind = 0, best_tissue = fm.tissue(t);  // kind: 0 edge removal, 1 2-3
      int best_wedge = -1;                            // the tet that changes tissue, if any
      auto consider = [&](bool ok, int kind, int tissue, int wedge) {
        if (!ok) return;
        double q_new = 1e300, q_old = 1e300;
        for (const auto& n : cand) q_new = std::min(q_new, n.quality);
        for (int o : cand_old) q_old = std::min(q_old, fm.quality(o));
        if (q_new > q_old + 1e-9 && q_new > best_q) {
          best_q = q_new;
          best_new = cand;
          best_old = cand_old;
          best_kind = kind;
          best_tissue = tissue;
          best_wedge = wedge;
        }
      };
      const auto T = fm.tet(t);
      for (const auto& e : kEdges) {
        // Inside t's tissue, or giving one thin wedge of the ring (not t) to t's tissue.
        int neighbour = -1;
        const bool ok = fm.try_edge_removal(t, T[e[0]], T[e[1]], fm.tissue(t), cand, cand_old,
                                            allow_interface_flips ? &neighbour : nullptr);
        consider(ok, 0, fm.tissue(t), neighbour);
        // Giving t itself, a thin wedge, to the tissue around the edge.
        const int wedge = allow_interface_flips ? fm.wedge_tissue(t, T[e[0]], T[e[1]]) : -1;
        if (wedge > 0) consider(fm.try_edge_removal(t, T[e[0]], T[e[1]], wedge, cand, cand_old), 0, wedge, t);
      }
      for (int f = 0; f < 4; ++f) consider(fm.try_23(t, f, cand, cand_old), 1, fm.tissue(t), -1);
      if (best_q < 0) continue;
      if (best_wedge >= 0) {
        ++r.interface_flips;
        r.volume_relabelled_mm3 += fm.volume(fm.tet(best_wedge));
      }
      fm.apply(best_old, best_new, best_tissue);
      ++applied;
      ++(best_kind == 1 ? r.flips_23 : r.edge_removals);
    }
    if (applied == 0) break;
  }
  fm.compact();
  return r;
}

}  // namespace tissuemesh
