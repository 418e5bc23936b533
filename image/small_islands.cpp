// Why: a tissue component of a few voxels (segmentation noise, e.g. one fat voxel inside glandular
// tissue) becomes a closed surface of its own. The remesher cannot collapse a closed component
// below a tetrahedron, so it survives as a pocket of edges far shorter than the mesh's, and every
// tet around it is badly shaped: such pockets set the worst radius-edge ratios of both volume
// meshers. Nothing that small is resolved by the mesh.
#include "image/small_islands.h"

#include "image/label_components.h"

#include <algorithm>
#include <map>
#include <stdexcept>
#include <unordered_set>
#include <vector>

namespace tissuemesh {

namespace {

constexpr int kMaxPasses = 10;

// The face neighbours of voxel v inside the image (their indices appended to `out`).
void face_neighbours(const LabelImage& ids, std::size_t v, std::vector<std::size_t>& out) {
  const int nx = ids.dims[0], ny = ids.dims[1], nz = ids.dims[2];
  const int i = static_cast<int>(v % nx), j = static_cast<int>((v / nx) % ny),
            k = static_cast<int>(v / (static_cast<std::size_t>(nx) * ny));
  const std::size_t sy = static_cast<std::size_t>(nx), sz = sy * static_cast<std::size_t>(ny);
  if (i > 0) out.push_back(v - 1);
  if (i + 1 < nx) out.push_back(v + 1);
  if (j > 0) out.push_back(v - sy);
  if (j + 1 < ny) out.push_back(v + sy);
  if (k > 0) out.push_back(v - sz);
  if (k + 1 < nz) out.push_back(v + sz);
}

// True when a component of `ids` with a voxel in `seeds` has fewer than `min_voxels` voxels. Each
// search from a seed stops once it has met min_voxels voxels of the seed's component.
bool small_component_at(const LabelImage& ids, const std::vector<std::size_t>& seeds, std::size_t min_voxels) {
  std::unordered_set<std::size_t> met;
  std::vector<std::size_t> stack, next;
  for (const std::size_t seed : seeds) {
    const std::int32_t id = ids.labels[seed];
    if (id == 0) continue;  // outside is no component
    met.clear();
    met.insert(seed);
    stack.assign(1, seed);
    while (!stack.empty() && met.size() < min_voxels) {
      const std::size_t v = stack.back();
      stack.pop_back();
      next.clear();
      face_neighbours(ids, v, next);
      for (const std::size_t w : next)
        if (ids.labels[w] == id && met.insert(w).second) stack.push_back(w);
    }
    if (met.size() < min_voxels) return true;
  }
  return false;
}

// One pass over the components of `ids` as they are now; returns the islands relabelled and
// appends the voxels it relabelled to `changed`. A tissue's largest component (the first of
// equals) is never an island, whatever its size: `kept` gets tissue id -> its voxels when it is
// under min_voxels.
std::size_t absorb_once(LabelImage& ids, std::size_t min_voxels, std::vector<std::size_t>& changed,
                        std::map<int, std::size_t>& kept) {
  const ComponentMap map = find_components(ids);
  std::map<std::int32_t, std::size_t> largest;  // tissue id -> index of its largest component
  for (std::size_t c = 0; c < map.components.size(); ++c) {
    const auto [it, added] = largest.emplace(map.components[c].tissue_id, c);
    if (!added && map.components[c].voxels > map.components[it->second].voxels) it->second = c;
  }
  std::vector<char> island(map.components.size(), 0);
  bool any = false;
  for (std::size_t c = 0; c < map.components.size(); ++c) {
    island[c] = map.components[c].voxels < min_voxels && largest.at(map.components[c].tissue_id) != c;
    any = any || island[c];
  }
  for (const auto& [id, c] : largest)
    if (map.components[c].voxels < min_voxels) kept[id] = map.components[c].voxels;
  if (!any) return 0;
  std::vector<std::vector<std::size_t>> voxels(map.components.size());
  for (std::size_t v = 0; v < map.component_of_voxel.size(); ++v) {
    const std::int32_t c = map.component_of_voxel[v];
    if (c >= 0 && island[static_cast<std::size_t>(c)]) voxels[static_cast<std::size_t>(c)].push_back(v);
  }
  const int nx = ids.dims[0], ny = ids.dims[1], nz = ids.dims[2];
  std::size_t absorbed = 0;
  for (std::size_t c = 0; c < map.components.size(); ++c) {
    if (voxels[c].empty()) continue;
    const std::int32_t own = map.components[c].tissue_id;
    std::map<std::int32_t, std::size_t> votes;  // ordered: ties go to the lowest id
    for (const std::size_t v : voxels[c]) {
      const int i = static_cast<int>(v % nx), j = static_cast<int>((v / nx) % ny),
                k = static_cast<int>(v / (static_cast<std::size_t>(nx) * ny));
      const int n[6][3] = {{i - 1, j, k}, {i + 1, j, k}, {i, j - 1, k}, {i, j + 1, k}, {i, j, k - 1}, {i, j, k + 1}};
      for (const auto& q : n) {
        const bool inside = q[0] >= 0 && q[0] < nx && q[1] >= 0 && q[1] < ny && q[2] >= 0 && q[2] < nz;
        const std::int32_t id = inside ? ids.at(q[0], q[1], q[2]) : 0;
        if (id != own) ++votes[id];
      }
    }
    // Every neighbour took this island's id earlier in the pass (its shell was an island too):
    // it is part of the region around it now.
    if (votes.empty()) continue;
    std::int32_t best = 0;
    std::size_t most = 0;
    for (const auto& [id, count] : votes)
      if (count > most) best = id, most = count;
    for (const std::size_t v : voxels[c]) ids.labels[v] = best;
    changed.insert(changed.end(), voxels[c].begin(), voxels[c].end());
    ++absorbed;
  }
  return absorbed;
}

// Per tissue, from the net change between `before` and `ids`. A component of `before` with a
// changed voxel was an island: a component with min_voxels voxels or more keeps all of them (every
// component that contains it later is at least as large), so each flood fill below stays inside
// one island. An island that went and came back whole (a pocket of tissue A in a small shell of
// B in A) changed nothing and is not counted.
std::vector<TissueIslands> count_by_tissue(const std::vector<std::int32_t>& before, const LabelImage& ids) {
  std::map<int, TissueIslands> per;
  std::unordered_set<std::size_t> visited;
  std::vector<std::size_t> stack, next;
  const double voxel_mm3 = ids.voxel_volume();
  for (std::size_t v = 0; v < before.size(); ++v) {
    if (before[v] == ids.labels[v]) continue;
    TissueIslands& t = per[before[v]];
    t.tissue_id = before[v];
    ++t.voxels;
    t.volume_mm3 += voxel_mm3;
    ++t.voxels_into[ids.labels[v]];
    if (!visited.insert(v).second) continue;
    ++t.islands;
    stack.assign(1, v);
    while (!stack.empty()) {
      const std::size_t u = stack.back();
      stack.pop_back();
      next.clear();
      face_neighbours(ids, u, next);
      for (const std::size_t w : next)
        if (before[w] == before[v] && visited.insert(w).second) stack.push_back(w);
    }
  }
  std::vector<TissueIslands> out;
  for (auto& [id, t] : per) out.push_back(std::move(t));
  return out;
}

}  // namespace

void IslandAbsorption::add(const IslandAbsorption& later) {
  islands += later.islands;
  voxels += later.voxels;
  volume_mm3 += later.volume_mm3;
  complete = later.complete;
  min_voxels = later.min_voxels;
  for (const auto& [id, n] : later.kept_whole) kept_whole[id] = n;
  for (const TissueIslands& l : later.tissues) {
    auto it = std::lower_bound(tissues.begin(), tissues.end(), l.tissue_id,
                               [](const TissueIslands& t, int id) { return t.tissue_id < id; });
    if (it == tissues.end() || it->tissue_id != l.tissue_id) it = tissues.insert(it, TissueIslands{l.tissue_id, 0, 0, 0.0, {}});
    it->islands += l.islands;
    it->voxels += l.voxels;
    it->volume_mm3 += l.volume_mm3;
    for (const auto& [id, n] : l.voxels_into) it->voxels_into[id] += n;
  }
}

IslandAbsorption absorb_small_islands(LabelImage& ids, std::size_t min_voxels, const std::vector<std::size_t>* changed_since) {
  IslandAbsorption out;
  out.min_voxels = min_voxels;
  if (min_voxels <= 1) return out;
  const std::vector<std::int32_t> before = ids.labels;
  // A component that has no changed voxel and no changed face neighbour is one the caller's last
  // absorption left, so no island: only the components around the changes can be new islands.
  std::vector<std::size_t> seeds;
  if (changed_since) {
    seeds = *changed_since;
    for (const std::size_t v : *changed_since) {
      if (v >= ids.labels.size()) throw std::invalid_argument("absorb_small_islands: changed voxel outside the image");
      face_neighbours(ids, v, seeds);
    }
  }
  // An island inside another island takes that island's id and becomes part of it only for this
  // pass's component list; the next pass sees it as what it is now. Each pass that changes
  // anything removes islands, so a few passes suffice; the cap only guards pathological labelings.
  // A pass after one that changed something looks for islands only among the components of the
  // voxels it relabelled (whole islands: the components they left lost no voxels otherwise), and
  // labels the whole image only when it finds one there; the outcome is the same.
  out.complete = false;
  for (int pass = 0; pass < kMaxPasses && !out.complete; ++pass) {
    if ((pass > 0 || changed_since) && !small_component_at(ids, seeds, min_voxels)) {
      out.complete = true;
      break;
    }
    seeds.clear();
    out.kept_whole.clear();
    out.complete = absorb_once(ids, min_voxels, seeds, out.kept_whole) == 0;
  }
  out.tissues = count_by_tissue(before, ids);
  for (const TissueIslands& t : out.tissues) {
    out.islands += t.islands;
    out.voxels += t.voxels;
    out.volume_mm3 += t.volume_mm3;
  }
  return out;
}

}  // namespace tissuemesh
