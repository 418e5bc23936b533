// Why: CGAL Mesh_3 finds a subdomain only if an initial point lands on its surface, so small
// isolated parts (FGT islands, tumour satellites) are silently left out unless every component
// gets seeds. The same components let the report name any part that did not make it into the mesh.
#include "image/label_components.h"

#include <algorithm>

namespace tissuemesh {

ComponentMap find_components(const LabelImage& img) {
  const int nx = img.dims[0], ny = img.dims[1], nz = img.dims[2];
  ComponentMap out;
  out.component_of_voxel.assign(img.voxel_count(), -1);
  // The stack holds each voxel's index with its coordinates (no divisions to recover them).
  struct Voxel {
    std::size_t index;
    int i, j, k;
  };
  std::vector<Voxel> stack;
  const std::ptrdiff_t sx = 1, sy = nx, sz = static_cast<std::ptrdiff_t>(nx) * ny;

  // Scan order gives each component its first voxel as seed; that voxel has no same-component
  // neighbour at lower index, so it lies on the component's boundary (or the image border).
  for (int k = 0; k < nz; ++k) {
    for (int j = 0; j < ny; ++j) {
      for (int i = 0; i < nx; ++i) {
        const std::size_t start = img.index(i, j, k);
        const std::int32_t id = img.labels[start];
        if (id == 0 || out.component_of_voxel[start] >= 0) continue;
        const std::int32_t comp = static_cast<std::int32_t>(out.components.size());
        LabelComponent c;
        c.tissue_id = id;
        c.seed = {i, j, k};
        c.box_min = {i, j, k};
        c.box_max = {i, j, k};
        Eigen::Vector3d sum_ijk = Eigen::Vector3d::Zero();
        out.component_of_voxel[start] = comp;
        stack.assign(1, {start, i, j, k});
        while (!stack.empty()) {
          const Voxel p = stack.back();
          stack.pop_back();
          const std::size_t v = p.index;
          const int vi = p.i, vj = p.j, vk = p.k;
          ++c.voxels;
          sum_ijk += Eigen::Vector3d(vi, vj, vk);
          c.box_min = {std::min(c.box_min[0], vi), std::min(c.box_min[1], vj),
                       std::min(c.box_min[2], vk)};
          c.box_max = {std::max(c.box_max[0], vi), std::max(c.box_max[1], vj),
                       std::max(c.box_max[2], vk)};
          auto visit = [&](bool inside, std::ptrdiff_t step, int wi, int wj, int wk) {
            if (!inside) return;
            const std::size_t w = static_cast<std::size_t>(static_cast<std::ptrdiff_t>(v) + step);
            if (img.labels[w] == id && out.component_of_voxel[w] < 0) {
              out.component_of_voxel[w] = comp;
              stack.push_back({w, wi, wj, wk});
            }
          };
          visit(vi > 0, -sx, vi - 1, vj, vk);
          visit(vi + 1 < nx, sx, vi + 1, vj, vk);
          visit(vj > 0, -sy, vi, vj - 1, vk);
          visit(vj + 1 < ny, sy, vi, vj + 1, vk);
          visit(vk > 0, -sz, vi, vj, vk - 1);
          visit(vk + 1 < nz, sz, vi, vj, vk + 1);
        }
        c.centroid_mm = img.to_physical(sum_ijk / static_cast<double>(c.voxels));
        out.components.push_back(c);
      }
    }
  }
  // Renumber so that components are grouped by tissue id (stable: scan order within a tissue).
  std::vector<std::int32_t> order(out.components.size());
  for (std::size_t c = 0; c < order.size(); ++c) order[c] = static_cast<std::int32_t>(c);
  std::stable_sort(order.begin(), order.end(), [&](std::int32_t a, std::int32_t b) {
    return out.components[a].tissue_id < out.components[b].tissue_id;
  });
  std::vector<std::int32_t> new_index(order.size());
  std::vector<LabelComponent> sorted(order.size());
  for (std::size_t n = 0; n < order.size(); ++n) {
    new_index[order[n]] = static_cast<std::int32_t>(n);
    sorted[n] = out.components[order[n]];
  }
  out.components.swap(sorted);
  for (auto& c : out.component_of_voxel)
    if (c >= 0) c = new_index[c];
  return out;
}

}  // namespace tissuemesh
