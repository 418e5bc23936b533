// Why scaling and not projection: the label interface of a blob a few voxels across has no
// trustworthy shape to project onto (it is a staircase, smoothed); its voxel volume is what the
// segmentation does say. Scaling keeps the shape Mesh_3 chose and its quality nearly unchanged.
#include "volume/component_volume_fit.h"

#include "quality/mesh_quality.h"
#include "quality/tet_faces.h"

#include <algorithm>
#include <cmath>

namespace tissuemesh {

ComponentVolumeFit fit_component_volumes(TetMesh& mesh, const std::vector<std::int32_t>& tet_component,
                                         const std::vector<ComponentTarget>& targets, double max_voxel_volume_mm3,
                                         double max_scale, double min_dihedral_deg) {
  ComponentVolumeFit fit;
  const std::size_t nt = mesh.tets.size(), np = mesh.points.size();
  if (nt == 0 || targets.empty()) return fit;

  // Vertex -> tets (CSR) and vertices on the outer boundary.
  std::vector<std::size_t> start(np + 1, 0);
  for (const auto& t : mesh.tets)
    for (int v : t) ++start[v + 1];
  for (std::size_t i = 0; i < np; ++i) start[i + 1] += start[i];
  std::vector<std::size_t> fill(start.begin(), start.end() - 1);
  std::vector<std::uint32_t> incident(start[np]);
  for (std::size_t t = 0; t < nt; ++t)
    for (int v : mesh.tets[t]) incident[fill[v]++] = static_cast<std::uint32_t>(t);
  std::vector<char> on_boundary(np, 0);
  {
    const TetFaces faces = number_tet_faces(mesh.tets);
    std::vector<std::uint8_t> uses(faces.count, 0);
    for (std::size_t t = 0; t < nt; ++t)
      for (int q = 0; q < 4; ++q) ++uses[faces.of(t, q)];
    for (std::size_t t = 0; t < nt; ++t)
      for (int q = 0; q < 4; ++q)
        if (uses[faces.of(t, q)] == 1)
          for (int k = 0; k < 4; ++k)
            if (k != q) on_boundary[mesh.tets[t][k]] = 1;
  }

  // Tets per component (only tets of the component's own tissue).
  std::vector<std::vector<std::uint32_t>> members(targets.size());
  for (std::size_t t = 0; t < nt; ++t) {
    const std::int32_t c = tet_component[t];
    if (c >= 0 && static_cast<std::size_t>(c) < targets.size() && mesh.tissue_ids[t] == targets[c].tissue)
      members[c].push_back(static_cast<std::uint32_t>(t));
  }

  auto volume_of = [&](std::uint32_t t) {
    const auto& q = mesh.tets[t];
    return signed_tet_volume(mesh.points[q[0]], mesh.points[q[1]], mesh.points[q[2]], mesh.points[q[3]]);
  };
  auto angle_of = [&](std::uint32_t t) {
    const auto& q = mesh.tets[t];
    return tet_volume_and_min_dihedral(mesh.points[q[0]], mesh.points[q[1]], mesh.points[q[2]], mesh.points[q[3]])
        .min_dihedral_deg;
  };

  std::vector<std::int32_t> owner(nt, -1);  // component of each member tet
  for (std::size_t c = 0; c < targets.size(); ++c)
    for (std::uint32_t t : members[c]) owner[t] = static_cast<std::int32_t>(c);

  for (std::size_t c = 0; c < targets.size(); ++c) {
    if (members[c].empty() || targets[c].volume_mm3 > max_voxel_volume_mm3) continue;
    double volume = 0.0;
    Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
    for (std::uint32_t t : members[c]) {
      const double v = volume_of(t);
      volume += v;
      for (int k : mesh.tets[t]) centroid += v / 4.0 * mesh.points[k];
    }
    if (!(volume > 0) || std::abs(targets[c].volume_mm3 / volume - 1.0) < 0.01) continue;
    centroid /= volume;

    // Vertices of the component; every tet around them must be the component's or of one other
    // tissue, and none may be on the outer boundary.
    std::vector<int> verts;
    for (std::uint32_t t : members[c])
      for (int k : mesh.tets[t]) verts.push_back(k);
    std::sort(verts.begin(), verts.end());
    verts.erase(std::unique(verts.begin(), verts.end()), verts.end());
    int other = -1;
    bool enclosed = true;
    std::vector<std::uint32_t> affected;
    for (int v : verts) {
      if (on_boundary[v]) enclosed = false;
      for (std::size_t i = start[v]; i < start[v + 1] && enclosed; ++i) {
        const std::uint32_t t = incident[i];
        affected.push_back(t);
        if (owner[t] == static_cast<std::int32_t>(c)) continue;
        const int tissue = mesh.tissue_ids[t];
        if (tissue == targets[c].tissue || (other >= 0 && tissue != other)) enclosed = false;
        other = tissue;
      }
      if (!enclosed) break;
    }
    if (!enclosed) {
      ++fit.not_enclosed;
      continue;
    }
    std::sort(affected.begin(), affected.end());
    affected.erase(std::unique(affected.begin(), affected.end()), affected.end());
    std::vector<double> floor_angle(affected.size());
    for (std::size_t i = 0; i < affected.size(); ++i) floor_angle[i] = std::min(min_dihedral_deg, angle_of(affected[i]));

    std::vector<Eigen::Vector3d> before(verts.size());
    for (std::size_t i = 0; i < verts.size(); ++i) before[i] = mesh.points[verts[i]];
    double lambda = std::clamp(std::cbrt(targets[c].volume_mm3 / volume), 1.0 / max_scale, max_scale);
    bool done = false;
    for (int attempt = 0; attempt < 4 && !done; ++attempt, lambda = 1.0 + 0.5 * (lambda - 1.0)) {
      for (std::size_t i = 0; i < verts.size(); ++i) mesh.points[verts[i]] = centroid + lambda * (before[i] - centroid);
      done = true;
      for (std::size_t i = 0; i < affected.size() && done; ++i) {
        const double a = angle_of(affected[i]);
        if (!(volume_of(affected[i]) > 0) || !(a >= floor_angle[i])) done = false;
      }
    }
    if (!done) {
      for (std::size_t i = 0; i < verts.size(); ++i) mesh.points[verts[i]] = before[i];
      ++fit.blocked;
      continue;
    }
    ++fit.fitted;
    double after = 0.0;
    for (std::uint32_t t : members[c]) after += volume_of(t);
    fit.volume_moved_mm3 += std::abs(after - volume);
  }
  return fit;
}

}  // namespace tissuemesh
