#include "core/tri_surface.h"

#include "core/errors.h"


namespace tissuemesh {

void TriSurface::validate(const std::string& what) const {
  const int n = static_cast<int>(points.size());
  const int regions = static_cast<int>(tissue_names.size());
  if (labels.size() != triangles.size())
    throw InputError(what + ": " + std::to_string(triangles.size()) + " triangles but " +
                     std::to_string(labels.size()) + " label pairs");
  for (int v = 0; v < n; ++v)
    if (!points[v].allFinite()) throw InputError(what + ": point " + std::to_string(v) + " is not finite");
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    const auto& tri = triangles[t];
    const std::string name = what + ": triangle " + std::to_string(t);
    for (int a : tri)
      if (a < 0 || a >= n) throw InputError(name + " uses point " + std::to_string(a) + " of " + std::to_string(n));
    if (tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2]) throw InputError(name + " repeats a vertex");
    const auto& pq = labels[t];
    if (pq[0] < 0 || pq[1] > regions || pq[0] >= pq[1])
      throw InputError(name + " has regions (" + std::to_string(pq[0]) + "|" + std::to_string(pq[1]) +
                       "): need 0 <= p < q <= " + std::to_string(regions));
  }
  for (std::size_t j = 0; j < junctions.size(); ++j) {
    if (junctions[j].size() < 2) throw InputError(what + ": junction " + std::to_string(j) + " has fewer than 2 points");
    for (int a : junctions[j])
      if (a < 0 || a >= n)
        throw InputError(what + ": junction " + std::to_string(j) + " uses point " + std::to_string(a));
  }
}

void TriSurface::tissue_boundary(int id, std::vector<int>& triangle_ids, std::vector<char>& reversed) const {
  triangle_ids.clear();
  reversed.clear();
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    if (labels[t][0] == id || labels[t][1] == id) {
      triangle_ids.push_back(static_cast<int>(t));
      reversed.push_back(labels[t][1] == id);
    }
  }
}

}  // namespace tissuemesh
