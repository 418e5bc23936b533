// The intersection guard of RemeshComplex (surface/remesh_complex.h): the grid of live triangle
// boxes, kept current as operations change triangles, and the test of an operation's new
// triangles against each other and against the live triangles near them.
#include "surface/remesh_complex.h"

#include <optional>

#include <omp.h>

namespace tissuemesh {
namespace {

/// The intersection guard's grid is rebuilt when the mean triangle size has drifted this far from
/// its cell size (coarsening grows triangles ~3x over the first rounds).
constexpr double kGridDrift = 1.5;
/// Grid cell edge over the mean triangle extent (largest box side): fewer cells per query against
/// more triangles per cell. With one query over all of an operation's created triangles
/// (would_intersect) the remeshing time is flat between 2 and 3 and grows on either side; the
/// output does not depend on it.
constexpr double kGridCellPerExtent = 2.5;

Eigen::AlignedBox3d box_of(const TrianglePoints& p) {
  Eigen::AlignedBox3d b(p[0]);
  b.extend(p[1]);
  b.extend(p[2]);
  return b;
}

}  // namespace

RemeshComplex::Scratch& RemeshComplex::scratch() { return scratch_[omp_get_thread_num() == 0 ? 0 : 1]; }

bool RemeshComplex::would_intersect(const std::vector<int>& replaced) {
  Scratch& sc = scratch();
  const std::vector<NewTriangle>& created = sc.created;
  if (created.empty()) return false;
  sc.created_boxes.clear();
  sc.created_prepared.clear();
  Eigen::AlignedBox3d all;
  for (const NewTriangle& c : created) {
    sc.created_boxes.push_back(box_of(c.p));
    sc.created_prepared.emplace_back(c.p);
    all.extend(sc.created_boxes.back());
  }
  for (std::size_t i = 0; i < created.size(); ++i)
    for (std::size_t j = i + 1; j < created.size(); ++j)
      if (triangles_intersect(sc.created_prepared[i], created[i].v, sc.created_prepared[j], created[j].v)) return true;
  // One grid query over the union of the created triangles' boxes, each live triangle met there
  // tested once against every created triangle whose box it touches: the same pairs as a query
  // per created triangle, without visiting a candidate once per created triangle.
  if (sc.seen.size() < tri_.size()) sc.seen.resize(tri_.size(), 0);
  ++sc.stamp;
  for (int t : replaced) sc.seen[t] = sc.stamp;
  sc.candidates.clear();
  grid_.query(all, sc.candidates);
  for (int u : sc.candidates) {
    if (sc.seen[u] == sc.stamp || !tri_alive_[u]) continue;
    sc.seen[u] = sc.stamp;
    const Eigen::AlignedBox3d& box = tri_box_[u];
    if (!box.intersects(all)) continue;
    std::optional<PreparedTriangle> prepared;  // built at the first created triangle whose box u touches
    for (std::size_t i = 0; i < created.size(); ++i) {
      if (!box.intersects(sc.created_boxes[i])) continue;
      if (!prepared) prepared.emplace(TrianglePoints{x_[tri_[u][0]], x_[tri_[u][1]], x_[tri_[u][2]]});
      if (triangles_intersect(sc.created_prepared[i], created[i].v, *prepared, tri_[u])) return true;
    }
  }
  return false;
}

void RemeshComplex::index_triangle(int t) {
  if (t >= static_cast<int>(tri_box_.size())) tri_box_.resize(tri_.size());
  tri_box_[t] = box_of({x_[tri_[t][0]], x_[tri_[t][1]], x_[tri_[t][2]]});
  grid_.insert(t, tri_box_[t]);
}

void RemeshComplex::rebuild_grid() {
  // Cells 2.5 times the mean triangle size (kGridCellPerExtent): a query visits a few cells of a
  // few triangles each.
  // Every change is entered as it happens, so the grid is only rebuilt when the triangles' size
  // has drifted by more than a factor kGridDrift from the cell size.
  double extent = 0.0;
  std::size_t n = 0;
  for (std::size_t t = 0; t < tri_.size(); ++t)
    if (tri_alive_[t]) {
      extent += box_of({x_[tri_[t][0]], x_[tri_[t][1]], x_[tri_[t][2]]}).sizes().maxCoeff();
      ++n;
    }
  const double cell = kGridCellPerExtent * (n > 0 && extent > 0.0 ? extent / static_cast<double>(n) : 1.0);
  if (grid_cell_ > 0.0 && cell < kGridDrift * grid_cell_ && cell > grid_cell_ / kGridDrift) return;
  grid_cell_ = cell;
  grid_.reset(cell, region_);
  for (std::size_t t = 0; t < tri_.size(); ++t)
    if (tri_alive_[t]) index_triangle(static_cast<int>(t));
}

}  // namespace tissuemesh
