// Why: sorting the 4n face keys is several times cheaper than a hash map of the faces, and gives
// ids in a fixed order.
#include "quality/tet_faces.h"

#include "core/face_key.h"

#include <algorithm>
#include <cstdint>
#include <utility>

namespace tissuemesh {

TetFaces number_tet_faces(const std::vector<std::array<int, 4>>& tets) {
  std::vector<std::pair<std::uint64_t, int>> keyed(4 * tets.size());
  for (std::size_t i = 0; i < tets.size(); ++i) {
    const auto& t = tets[i];
    for (int q = 0; q < 4; ++q)
      keyed[4 * i + q] = {face_key(t[(q + 1) % 4], t[(q + 2) % 4], t[(q + 3) % 4]), static_cast<int>(4 * i + q)};
  }
  std::sort(keyed.begin(), keyed.end());
  TetFaces f;
  f.id.resize(keyed.size());
  for (std::size_t k = 0; k < keyed.size(); ++k) {
    if (k > 0 && keyed[k].first != keyed[k - 1].first) ++f.count;
    f.id[static_cast<std::size_t>(keyed[k].second)] = static_cast<int>(f.count);
  }
  if (!keyed.empty()) ++f.count;
  return f;
}

}  // namespace tissuemesh
