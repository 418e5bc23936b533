// Shared by the volume-mesher tests of surface complexes (CGAL and TetGen): the small
// test images remeshed to a budget, the interfaces a tet mesh has, and its per-tissue volumes.
#pragma once

#include "core/tet_mesh.h"
#include "quality/conformity.h"
#include "surface/surface_projection.h"
#include "surface/surface_remesh.h"
#include "support/surface_images.h"

#include <set>
#include <utility>
#include <vector>

namespace tissuemesh::test {

inline RemeshResult remeshed(const LabelImage& img, int n_tissues, int budget) {
  const TriSurface input = extract(img, n_tissues).surface;
  const SurfaceProjection on_input(input);
  RemeshOptions options;
  options.target_vertices = budget;
  options.max_deviation_mm = 0.5 * img.spacing.norm();
  Progress progress;
  return remesh_surface(input, on_input, options, progress);
}

/// The region pairs that share at least one face of the mesh (0 = outside).
inline std::set<std::pair<int, int>> interfaces(const ConformityReport& r) {
  std::set<std::pair<int, int>> out;
  for (const auto& [pair, count] : r.interface_faces) out.insert(pair);
  return out;
}

/// Signed volume per tissue id (index 0 unused), mm^3.
inline std::vector<double> tissue_volumes(const TetMesh& m) {
  std::vector<double> volume(m.num_tissues() + 1, 0.0);
  for (std::size_t t = 0; t < m.tets.size(); ++t) {
    const auto& k = m.tets[t];
    volume[m.tissue_ids[t]] += signed_tet_volume(m.points[k[0]], m.points[k[1]], m.points[k[2]], m.points[k[3]]);
  }
  return volume;
}

}  // namespace tissuemesh::test
