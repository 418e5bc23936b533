#include "mesher/small_islands.h"

#include "mesher/label_components.h"

#include <map>
#include <vector>

namespace tissuemesh {

namespace {

constexpr int kMaxPasses = 10;

// One pass over the components of `ids` as they are now; returns the islands relabelled.
std::size_t absorb_once(LabelImage& ids, std::size_t min_voxels) {
  const ComponentMap map = find_components(ids);
  std::vector<std::vector<std::size_t>> voxels(map.components.size());
  bool any = false;
  for (std::size_t c = 0; c < map.components.size(); ++c) any = any || map.components[c].voxels < min_voxels;
  if (!any) return 0;
  for (std::size_t v = 0; v < map.component_of_voxel.size(); ++v) {
    const std::int32_t c = map.component_of_voxel[v];
    if (c >= 0 && map.components[static_cast<std::size_t>(c)].voxels < min_voxels) voxels[static_cast<std::size_t>(c)].push_back(v);
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
    ++absorbed;
  }
  return absorbed;
}

}  // namespace

IslandAbsorption absorb_small_islands(LabelImage& ids, std::size_t min_voxels) {
  IslandAbsorption out;
  if (min_voxels <= 1) return out;
  const std::vector<std::int32_t> before = ids.labels;
  // An island inside another island takes that island's id and becomes part of it only for this
  // pass's component list; the next pass sees it as what it is now. Each pass that changes
  // anything removes islands, so a few passes suffice; the cap only guards pathological labelings.
  for (int pass = 0; pass < kMaxPasses; ++pass) {
    const std::size_t n = absorb_once(ids, min_voxels);
    if (n == 0) break;
    out.islands += n;
  }
  for (std::size_t v = 0; v < before.size(); ++v) out.voxels += before[v] != ids.labels[v];
  return out;
}

}  // namespace tissuemesh
