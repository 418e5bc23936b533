// Partitioned sweeps of RemeshComplex (surface/remesh_complex.h): the collapse and relaxation
// sweeps of a large complex on two threads, with results that do not depend on the thread count.
//
// At the start of a sweep every live vertex gets a side from the slab of grid_ cells (across
// kSplitAxis) it is in: 0 below the median slab, 1 above it, -1 (the band) in it. An operation
// runs on its side's thread only when every vertex it reads or changes is on that side
// (vertex_on_side: the vertex, or the edge's two vertices, and every vertex of their triangles)
// and, for a move, when the new position stays in that side's slabs (point_on_side). Then the two
// threads share nothing that one of them writes:
//   - the triangles a side changes have all their vertices on it, so their old and new boxes lie
//     in its slabs, and its intersection guard reads only cells of its slabs (those of the union
//     of the boxes of the triangles it would create); the grid's cells all exist from its reset()
//     on (surface/triangle_grid.h), so entering a triangle writes only cells of its own side;
//   - the vertex and triangle arrays are written at the side's own entries, and a side reads
//     another vertex's triangle list only after finding that vertex on its side; the junction
//     bookkeeping (curve_edge_) is only read (a collapse of an edge between two junction vertices
//     rewrites it, and waits for the band);
//   - each thread has its own guard scratch (scratch()) and counts its collapses there; an
//     exception on either thread is rethrown after both finished (surface/run_at_once.h).
// Everything else an operation reads (the size field and cap, the projections onto the reference,
// L, the deviation bound) does not change during a sweep, and its queries are safe on two
// threads. So each half has the result it would have alone, whichever thread runs it and whether
// the other runs at the same time; then the band (every operation not done on a side, in index
// order) runs on one thread. With threads_ 1 the halves run one after the other.
//
// Why: the collapse and relaxation sweeps take most of the remeshing time. The split axis is y:
// the axis decides which operations wait for the band, hence the (equally valid) surface, and
// with x or z the shipped 2.1K surface fell short of Table 1 of Alqaoud et al.
#include "surface/remesh_complex.h"

#include "surface/run_at_once.h"

#include <algorithm>

namespace tissuemesh {
namespace {

/// Below this many live vertices a sweep is not split: it takes milliseconds, and the band would
/// hold a large share of it.
constexpr std::size_t kPartitionFrom = 10000;
/// The axis the halves are split across (see the comment at the top of this file).
constexpr int kSplitAxis = 1;

}  // namespace

bool RemeshComplex::assign_sides() {
  side_.assign(x_.size(), -1);
  if (alive_vertices_ < kPartitionFrom) return false;
  std::vector<int> slabs;
  slabs.reserve(alive_vertices_);
  for (std::size_t v = 0; v < x_.size(); ++v)
    if (vertex_alive_[v]) slabs.push_back(grid_.slab_of(x_[v][kSplitAxis], kSplitAxis));
  std::nth_element(slabs.begin(), slabs.begin() + slabs.size() / 2, slabs.end());
  band_slab_ = slabs[slabs.size() / 2];
  std::size_t count[2] = {0, 0};
  for (std::size_t v = 0; v < x_.size(); ++v) {
    if (!vertex_alive_[v]) continue;
    const int c = grid_.slab_of(x_[v][kSplitAxis], kSplitAxis);
    if (c != band_slab_) ++count[side_[v] = c < band_slab_ ? 0 : 1];
  }
  return count[0] > 0 && count[1] > 0;
}

bool RemeshComplex::vertex_on_side(int v, int side) const {
  if (side_[v] != side) return false;
  for (int t : vt_[v])
    for (int w : tri_[t])
      if (side_[w] != side) return false;
  return true;
}

bool RemeshComplex::point_on_side(const Vector3d& p, int side) const {
  const int c = grid_.slab_of(p[kSplitAxis], kSplitAxis);
  return side == 0 ? c < band_slab_ : c > band_slab_;
}

template <class Item, class SideOf, class Op>
std::size_t RemeshComplex::partitioned_sweep(const std::vector<Item>& items, SideOf side_of, Op op) {
  std::vector<char> done(items.size(), 0);
  std::size_t changed[2] = {0, 0};
  if (assign_sides()) {
    ++partitioned_sweeps;
    for (Scratch& sc : scratch_) {
      if (sc.seen.size() < tri_.size()) sc.seen.resize(tri_.size(), 0);  // no triangle is added below
      sc.collapsed = 0;
    }
    auto half = [&](int side) {
      std::size_t n = 0;
      for (std::size_t i = 0; i < items.size(); ++i) {
        if (side_of(items[i]) != side) continue;
        const int r = op(items[i], side);
        if (r < 0) continue;  // touches the band or the other side: the band's
        done[i] = 1;
        n += static_cast<std::size_t>(r);
      }
      changed[side] = n;
    };
    halves_running_ = true;  // try_collapse counts into scratch()
    try {
      run_at_once([&] { half(0); }, [&] { half(1); }, threads_);
    } catch (...) {
      halves_running_ = false;
      throw;
    }
    halves_running_ = false;
    for (Scratch& sc : scratch_) {
      alive_vertices_ -= sc.collapsed;
      collapses += sc.collapsed;
      sc.collapsed = 0;
    }
  }
  std::fill(side_.begin(), side_.end(), -1);
  std::size_t n = changed[0] + changed[1];
  for (std::size_t i = 0; i < items.size(); ++i)
    if (!done[i]) n += op(items[i], -1) > 0;
  return n;
}

std::size_t RemeshComplex::collapse_sweep(bool repeat) {
  rebuild_grid();
  if (repeat && ring_changed_.size() == x_.size())
    ring_changed_before_.swap(ring_changed_);
  else
    ring_changed_before_.assign(x_.size(), 1);
  ring_changed_.assign(x_.size(), 0);
  for (Scratch& sc : scratch_) sc.skipped = 0;
  // Marks only during the sweep: other operations (splits) grow the vertex arrays past them.
  struct Tracking {
    bool& on;
    explicit Tracking(bool& flag) : on(flag) { on = true; }
    ~Tracking() { on = false; }
  } tracking(tracking_rings_);
  const std::size_t n = partitioned_sweep(
      edges(), [this](const std::array<int, 2>& e) { return side_[e[0]] == side_[e[1]] ? side_[e[0]] : -1; },
      [this](const std::array<int, 2>& e, int side) { return collapse_edge(e[0], e[1], side); });
  for (const Scratch& sc : scratch_) skipped_collapse_tries += sc.skipped;
  return n;
}

std::size_t RemeshComplex::collapse_until_stable(int max_sweeps) {
  std::size_t n = 0;
  for (int k = 0; k < max_sweeps; ++k) {
    const std::size_t collapsed = collapse_sweep(k > 0);
    compact();
    n += collapsed;
    if (collapsed == 0) break;
  }
  return n;
}

void RemeshComplex::relax() {
  rebuild_grid();
  std::vector<int> vertices(x_.size());
  for (std::size_t v = 0; v < x_.size(); ++v) vertices[v] = static_cast<int>(v);
  partitioned_sweep(
      vertices, [this](int v) { return static_cast<int>(side_[v]); },
      [this](int v, int side) { return relax_vertex(v, side); });
}

}  // namespace tissuemesh
