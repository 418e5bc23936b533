#include "volume/sliver_splits.h"

#include "quality/mesh_quality.h"
#include "volume/wedge_relabel.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <utility>
#include <vector>

namespace tissuemesh {

namespace {

double min_angle(const std::vector<Eigen::Vector3d>& p, const std::array<int, 4>& t) {
  const TetVolumeAndAngle s = tet_volume_and_min_dihedral(p[t[0]], p[t[1]], p[t[2]], p[t[3]]);
  return s.volume_mm3 > 0 ? s.min_dihedral_deg : -std::numeric_limits<double>::infinity();
}

class Splitter {
 public:
  Splitter(TetMesh& mesh, double target_deg) : mesh_(mesh), target_deg_(target_deg), star_(mesh.points.size()) {
    for (std::size_t t = 0; t < mesh.tets.size(); ++t)
      for (int v : mesh.tets[t]) star_[v].push_back(t);
  }

  /// Tries the interior edges of tet t, longest first, then (when `relabel`) the edges around
  /// which t is a flat wedge in another tissue; true when one was split.
  bool try_tet(std::size_t t, bool relabel, SliverSplitResult& r) {
    const auto& k = mesh_.tets[t];
    std::vector<std::pair<double, std::pair<int, int>>> edges;
    for (int i = 0; i < 4; ++i)
      for (int j = i + 1; j < 4; ++j)
        edges.push_back({-(mesh_.points[k[i]] - mesh_.points[k[j]]).norm(), {k[i], k[j]}});
    std::sort(edges.begin(), edges.end());
    for (const auto& e : edges)
      if (try_edge(e.second.first, e.second.second)) return true;
    if (!relabel || !is_flat_wedge(mesh_, static_cast<int>(t))) return false;
    const int from = mesh_.tissue_ids[t];
    const double wedge_volume = std::abs(signed_volume(t));
    const AcrossFace across = [this](int a, int b, int c, int x) { return this->across(a, b, c, x); };
    for (const auto& e : edges) {
      const int to = sole_other_tissue(e.second.first, e.second.second, t);
      if (to < 0 || to == from || !relabel_keeps_topology(mesh_, static_cast<int>(t), to, across)) continue;
      mesh_.tissue_ids[t] = to;
      if (try_edge(e.second.first, e.second.second)) {
        ++r.relabelled_wedges;
        r.volume_relabelled_mm3 += wedge_volume;
        return true;
      }
      mesh_.tissue_ids[t] = from;
    }
    return false;
  }

 private:
  TetMesh& mesh_;
  double target_deg_;
  std::vector<std::vector<std::size_t>> star_;  ///< per node: its tets

  double signed_volume(std::size_t t) const {
    const auto& k = mesh_.tets[t];
    return signed_tet_volume(mesh_.points[k[0]], mesh_.points[k[1]], mesh_.points[k[2]], mesh_.points[k[3]]);
  }

  // The other tet than x on face (a, b, c), or -1.
  int across(int a, int b, int c, int x) const {
    for (std::size_t t : star_[a]) {
      if (static_cast<int>(t) == x) continue;
      const auto& k = mesh_.tets[t];
      if (std::find(k.begin(), k.end(), b) != k.end() && std::find(k.begin(), k.end(), c) != k.end())
        return static_cast<int>(t);
    }
    return -1;
  }

  // The tissue of every tet around edge (a, b) other than t, or -1 when they differ or none is.
  int sole_other_tissue(int a, int b, std::size_t t) const {
    int tissue = -1;
    for (std::size_t x : ring(a, b)) {
      if (x == t) continue;
      if (tissue >= 0 && mesh_.tissue_ids[x] != tissue) return -1;
      tissue = mesh_.tissue_ids[x];
    }
    return tissue;
  }

  std::vector<std::size_t> ring(int a, int b) const {
    std::vector<std::size_t> out;
    for (std::size_t t : star_[a]) {
      const auto& k = mesh_.tets[t];
      if (std::find(k.begin(), k.end(), b) != k.end()) out.push_back(t);
    }
    return out;
  }

  /// Every tet around (a, b) of one tissue and every face at the edge shared by two of them.
  bool interior(int a, int b, const std::vector<std::size_t>& around) const {
    if (around.size() < 3) return false;
    std::map<int, int> faces;  // the third node of each face at the edge -> tets holding it
    const int tissue = mesh_.tissue_ids[around[0]];
    for (std::size_t t : around) {
      if (mesh_.tissue_ids[t] != tissue) return false;
      for (int v : mesh_.tets[t])
        if (v != a && v != b) ++faces[v];
    }
    for (const auto& f : faces)
      if (f.second != 2) return false;  // a face at the edge with one tet: the boundary
    return true;
  }

  bool try_edge(int a, int b) {
    const std::vector<std::size_t> around = ring(a, b);
    if (!interior(a, b, around)) return false;
    double before = std::numeric_limits<double>::infinity();
    int below_before = 0;  // tets around the edge under the target
    for (std::size_t t : around) {
      const double q = min_angle(mesh_.points, mesh_.tets[t]);
      before = std::min(before, q);
      below_before += q < target_deg_;
    }
    // The split tets, with the new node as index `m` (appended to the points).
    const int m = static_cast<int>(mesh_.points.size());
    std::vector<std::array<int, 4>> split;
    for (std::size_t t : around) {
      std::array<int, 4> ta = mesh_.tets[t], tb = mesh_.tets[t];
      for (int i = 0; i < 4; ++i) {
        if (ta[i] == a) ta[i] = m;
        if (tb[i] == b) tb[i] = m;
      }
      split.push_back(ta);
      split.push_back(tb);
    }
    mesh_.points.push_back(0.5 * (mesh_.points[a] + mesh_.points[b]));
    auto star_min = [&] {
      double q = std::numeric_limits<double>::infinity();
      for (const auto& k : split) q = std::min(q, min_angle(mesh_.points, k));
      return q;
    };
    double best = star_min();
    // Compass search over the new node's position: six axis steps and the step halved when none helps.
    double step = 0.0;
    for (const auto& k : split)
      for (int v : k)
        if (v != m) step = std::max(step, (mesh_.points[v] - mesh_.points[m]).norm());
    step *= 0.25;
    for (int level = 0; level < 10; ++level, step *= 0.5) {
      bool moved = true;
      for (int round = 0; moved && round < 20; ++round) {
        moved = false;
        for (int d = 0; d < 6; ++d) {
          Eigen::Vector3d dir = Eigen::Vector3d::Zero();
          dir[d / 2] = d % 2 ? -1.0 : 1.0;
          const Eigen::Vector3d here = mesh_.points[m];
          mesh_.points[m] = here + step * dir;
          const double q = star_min();
          if (q > best) {
            best = q;
            moved = true;
          } else {
            mesh_.points[m] = here;
          }
        }
      }
    }
    // Kept when the smallest angle around the edge rises and no more of its tets are under the
    // target than before: a split that lifts the worst tet a little but leaves several new ones
    // under the target only spreads the sliver (repeated, a cluster of them).
    int below_after = 0;
    for (const auto& k : split) below_after += min_angle(mesh_.points, k) < target_deg_;
    if (!(best > before) || below_after > below_before) {
      mesh_.points.pop_back();
      return false;
    }
    // Keep it: each tet around the edge becomes its a -> m half in place, the b -> m half appended.
    star_.emplace_back();
    for (std::size_t i = 0; i < around.size(); ++i) {
      const std::size_t t = around[i];
      mesh_.tets[t] = split[2 * i];
      const std::size_t added = mesh_.tets.size();
      mesh_.tets.push_back(split[2 * i + 1]);
      mesh_.tissue_ids.push_back(mesh_.tissue_ids[t]);
      auto& sa = star_[a];
      sa.erase(std::find(sa.begin(), sa.end(), t));
      sa.push_back(added);
      star_[m].push_back(t);
      star_[m].push_back(added);
      for (int v : split[2 * i + 1])
        if (v != a && v != m) star_[v].push_back(added);
    }
    return true;
  }
};

}  // namespace

SliverSplitResult split_slivers(TetMesh& mesh, double target_deg, bool allow_interface_relabels, int max_passes) {
  SliverSplitResult r;
  Splitter splitter(mesh, target_deg);
  for (int pass = 0; pass < max_passes; ++pass) {
    std::vector<std::pair<double, std::size_t>> bad;
    for (std::size_t t = 0; t < mesh.tets.size(); ++t) {
      const double q = min_angle(mesh.points, mesh.tets[t]);
      if (q < target_deg) bad.push_back({q, t});
    }
    std::sort(bad.begin(), bad.end());
    std::size_t before = r.splits;
    for (const auto& [q, t] : bad) {
      if (min_angle(mesh.points, mesh.tets[t]) >= target_deg) continue;  // an earlier split fixed it
      if (splitter.try_tet(t, allow_interface_relabels, r)) ++r.splits;
    }
    if (r.splits == before) break;
  }
  return r;
}

}  // namespace tissuemesh
