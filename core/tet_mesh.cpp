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

}  // namespace tissuemesh
