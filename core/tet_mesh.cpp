#include "core/tet_mesh.h"

#include "core/errors.h"

#include <sstream>

namespace tissuemesh {

void TetMesh::validate(const std::string& what) const {
  std::ostringstream err;
  const int n = static_cast<int>(points.size());
  const int ntissues = static_cast<int>(tissue_names.size());
  if (tissue_ids.size() != tets.size()) {
    err << what << ": " << tets.size() << " tets but " << tissue_ids.size() << " tissue ids";
    throw InputError(err.str());
  }
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (!points[i].allFinite()) {
      err << what << ": node " << i << " has a non-finite coordinate";
      throw InputError(err.str());
    }
  }
  for (std::size_t t = 0; t < tets.size(); ++t) {
    for (int v : tets[t]) {
      if (v < 0 || v >= n) {
        err << what << ": tet " << t << " references node " << v << " but there are " << n
            << " nodes";
        throw InputError(err.str());
      }
    }
    if (tissue_ids[t] < 1 || tissue_ids[t] > ntissues) {
      err << what << ": tet " << t << " has tissue id " << tissue_ids[t] << " but only "
          << ntissues << " tissues are named";
      throw InputError(err.str());
    }
  }
}

void keep_tets(TetMesh& mesh, const std::vector<char>& keep) {
  std::vector<std::array<int, 4>> tets;
  std::vector<int> ids;
  for (std::size_t t = 0; t < mesh.tets.size(); ++t)
    if (keep[t]) {
      tets.push_back(mesh.tets[t]);
      ids.push_back(mesh.tissue_ids[t]);
    }
  std::vector<int> new_index(mesh.points.size(), -1);
  for (const auto& t : tets)
    for (int v : t) new_index[v] = 0;
  std::vector<Eigen::Vector3d> points;
  for (std::size_t v = 0; v < mesh.points.size(); ++v)
    if (new_index[v] == 0) {
      new_index[v] = static_cast<int>(points.size());
      points.push_back(mesh.points[v]);
    }
  for (auto& t : tets)
    for (int& v : t) v = new_index[v];
  mesh.points.swap(points);
  mesh.tets.swap(tets);
  mesh.tissue_ids.swap(ids);
}

}  // namespace tissuemesh
