// Why SurfaceNets rather than the deformable multi-material 2-simplex mesh (Rashid et al. 2017)
// that Alqaoud et al. use: it is linear in the voxel count, has no force weights to tune, and its
// constraints give the guarantees this stage needs (closed, oriented, shared interfaces, junctions
// kept) by construction rather than by convergence.
#include "surface/surface_extraction.h"

#include "core/errors.h"
#include "core/junction_tracing.h"
#include "surface/surface_checks.h"

#include <Eigen/LU>  // determinant()

#include <algorithm>
#include <array>
#include <cstdint>
#include <set>
#include <utility>

namespace tissuemesh {
namespace {

/// Taubin's lambda|mu pair (Taubin 1995): lambda smooths, mu (negative, |mu| > lambda) inflates
/// back; pass band k_pb = 1/lambda + 1/mu = 0.11, so the surface is smoothed without shrinking.
constexpr double kLambda = 0.5;
constexpr double kMu = -0.53;

/// Closed junction loops of at most this many edges are not smoothed (see extract_surface).
constexpr std::size_t kShortLoopEdges = 8;
/// Rounds of pulling folded vertices back towards their voxel corners (the last one puts them there).
constexpr int kUnfoldRounds = 6;

/// Label of voxel (i, j, k); outside the image = 0 (outside region).
struct PaddedLabels {
  const LabelImage& img;
  int operator()(int i, int j, int k) const {
    if (i < 0 || j < 0 || k < 0 || i >= img.dims[0] || j >= img.dims[1] || k >= img.dims[2]) return 0;
    return img.labels[img.index(i, j, k)];
  }
};

int distinct(std::array<int, 4> v) {
  std::sort(v.begin(), v.end());
  return static_cast<int>(std::unique(v.begin(), v.end()) - v.begin());
}


/// Vertices on voxel corners (lattice points) and the quads between them.
struct NetBuilder {
  const PaddedLabels label;
  const long long lx, ly;
  std::vector<int> vertex_of;             ///< lattice point -> vertex, -1 = none
  std::vector<std::array<int, 3>> lattice;  ///< vertex -> lattice point (I, J, K)
  std::vector<std::array<int, 4>> quads;  ///< normal from labels[0] into labels[1]
  std::vector<std::array<int, 2>> quad_labels;

  NetBuilder(const LabelImage& img)
      : label{img}, lx(img.dims[0] + 1), ly(img.dims[1] + 1),
        vertex_of(static_cast<std::size_t>(lx * ly * (img.dims[2] + 1)), -1) {}

  int find(int I, int J, int K) const {
    if (I < 0 || J < 0 || K < 0 || I >= lx || J >= ly) return -1;
    const long long at = I + lx * (J + ly * static_cast<long long>(K));
    return at < static_cast<long long>(vertex_of.size()) ? vertex_of[static_cast<std::size_t>(at)] : -1;
  }
  int vertex(int I, int J, int K) {
    int& v = vertex_of[static_cast<std::size_t>(I + lx * (J + ly * static_cast<long long>(K)))];
    if (v < 0) {
      v = static_cast<int>(lattice.size());
      lattice.push_back({I, J, K});
    }
    return v;
  }
  /// Quad with corners in the order whose normal points from voxel label `a` into `b`.
  void add(const std::array<int, 4>& v, int a, int b) {
    if (a < b) {
      quads.push_back(v);
      quad_labels.push_back({a, b});
    } else {
      quads.push_back({v[0], v[3], v[2], v[1]});
      quad_labels.push_back({b, a});
    }
  }

  void build(const std::array<int, 3>& d) {
    // Faces normal to x between voxels (i,j,k) and (i+1,j,k): lattice I = i + 1; corner order
    // (J,K) (J+1,K) (J+1,K+1) (J,K+1) turns about +x. Likewise for y (order in z, x) and z (x, y).
    for (int k = 0; k < d[2]; ++k)
      for (int j = 0; j < d[1]; ++j)
        for (int i = -1; i < d[0]; ++i) {
          const int a = label(i, j, k), b = label(i + 1, j, k);
          if (a != b) add({vertex(i + 1, j, k), vertex(i + 1, j + 1, k), vertex(i + 1, j + 1, k + 1), vertex(i + 1, j, k + 1)}, a, b);
        }
    for (int k = 0; k < d[2]; ++k)
      for (int j = -1; j < d[1]; ++j)
        for (int i = 0; i < d[0]; ++i) {
          const int a = label(i, j, k), b = label(i, j + 1, k);
          if (a != b) add({vertex(i, j + 1, k), vertex(i, j + 1, k + 1), vertex(i + 1, j + 1, k + 1), vertex(i + 1, j + 1, k)}, a, b);
        }
    for (int k = -1; k < d[2]; ++k)
      for (int j = 0; j < d[1]; ++j)
        for (int i = 0; i < d[0]; ++i) {
          const int a = label(i, j, k), b = label(i, j, k + 1);
          if (a != b) add({vertex(i, j, k + 1), vertex(i + 1, j, k + 1), vertex(i + 1, j + 1, k + 1), vertex(i, j + 1, k + 1)}, a, b);
        }
  }

  /// Junction neighbours of every vertex: lattice edges around which >= 3 regions meet.
  std::vector<std::vector<int>> junction_edges() const {
    std::vector<std::vector<int>> adj(lattice.size());
    for (std::size_t v = 0; v < lattice.size(); ++v) {
      const auto [I, J, K] = lattice[v];
      // The edge from (I,J,K) to the next lattice point along x passes through voxel column i = I,
      // between j = J-1, J and k = K-1, K (and likewise along y and z).
      const std::array<std::array<int, 4>, 3> around = {
          std::array<int, 4>{label(I, J - 1, K - 1), label(I, J, K - 1), label(I, J, K), label(I, J - 1, K)},
          std::array<int, 4>{label(I - 1, J, K - 1), label(I, J, K - 1), label(I, J, K), label(I - 1, J, K)},
          std::array<int, 4>{label(I - 1, J - 1, K), label(I, J - 1, K), label(I, J, K), label(I - 1, J, K)}};
      for (int axis = 0; axis < 3; ++axis) {
        if (distinct(around[axis]) < 3) continue;
        const int w = find(I + (axis == 0), J + (axis == 1), K + (axis == 2));
        if (w < 0) continue;  // cannot happen: >= 3 regions around an edge make it a quad edge
        adj[v].push_back(w);
        adj[static_cast<std::size_t>(w)].push_back(static_cast<int>(v));
      }
    }
    for (auto& a : adj) std::sort(a.begin(), a.end());
    return adj;
  }

  int regions_around(int v) const {
    const auto [I, J, K] = lattice[static_cast<std::size_t>(v)];
    std::array<int, 8> l{};
    for (int b = 0; b < 8; ++b) l[b] = label(I - 1 + (b & 1), J - 1 + (b >> 1 & 1), K - 1 + (b >> 2));
    std::sort(l.begin(), l.end());
    return static_cast<int>(std::unique(l.begin(), l.end()) - l.begin());
  }
};

/// Neighbours of every vertex along quad edges (sorted, unique).
std::vector<std::vector<int>> quad_neighbours(std::size_t n, const std::vector<std::array<int, 4>>& quads) {
  std::vector<std::vector<int>> adj(n);
  for (const auto& q : quads)
    for (int e = 0; e < 4; ++e) {
      adj[static_cast<std::size_t>(q[e])].push_back(q[(e + 1) % 4]);
      adj[static_cast<std::size_t>(q[(e + 1) % 4])].push_back(q[e]);
    }
  for (auto& a : adj) {
    std::sort(a.begin(), a.end());
    a.erase(std::unique(a.begin(), a.end()), a.end());
  }
  return adj;
}

/// Taubin relaxation in voxel-index coordinates with every vertex clamped to its voxel-centre box;
/// pinned vertices stay; curve vertices move along their curve neighbours.
void relax(std::vector<Eigen::Vector3d>& x, const std::vector<std::array<int, 3>>& lattice,
           const std::vector<VertexKind>& kind, const std::vector<char>& pinned, const std::vector<std::vector<int>>& surface_adj,
           const std::vector<std::vector<int>>& curve_adj, int iterations) {
  std::vector<Eigen::Vector3d> next = x;
  // Each vertex's neighbours (curve or surface ones, as it moves) in one flat list, in their order:
  // the 2 x iterations sweeps read them without a pointer per vertex (the same sums).
  std::vector<std::size_t> first(x.size() + 1, 0);
  std::vector<int> adjacent;
  for (std::size_t v = 0; v < x.size(); ++v) {
    const auto& n = kind[v] == VertexKind::Curve ? curve_adj[v] : surface_adj[v];
    if (!pinned[v]) adjacent.insert(adjacent.end(), n.begin(), n.end());
    first[v + 1] = adjacent.size();
  }
  for (int it = 0; it < 2 * iterations; ++it) {
    const double factor = it % 2 == 0 ? kLambda : kMu;
    // Each vertex's new position depends only on the old positions: the vertices split over two
    // threads give the same result.
    const std::int64_t count = static_cast<std::int64_t>(x.size());
#pragma omp parallel for schedule(static) num_threads(2)
    for (std::int64_t i = 0; i < count; ++i) {
      const auto v = static_cast<std::size_t>(i);
      if (pinned[v]) continue;
      Eigen::Vector3d mean = Eigen::Vector3d::Zero();
      for (std::size_t e = first[v]; e < first[v + 1]; ++e) mean += x[static_cast<std::size_t>(adjacent[e])];
      mean /= static_cast<double>(first[v + 1] - first[v]);
      Eigen::Vector3d p = x[v] + factor * (mean - x[v]);
      for (int a = 0; a < 3; ++a) p[a] = std::clamp(p[a], lattice[v][a] - 1.0, static_cast<double>(lattice[v][a]));
      next[v] = p;
    }
    std::swap(x, next);
  }
}

}  // namespace

namespace {
constexpr int kIslandRounds = 4;  // absorb + repair rounds; the phantom needs 2
}  // namespace

SurfaceExtraction extract_surface(const LabelImage& ids, const std::vector<std::string>& tissue_names,
                                  const SurfaceParams& params, Progress& progress) {
  const int regions = static_cast<int>(tissue_names.size());
  for (std::size_t i = 0; i < ids.labels.size(); ++i)
    if (ids.labels[i] < 0 || ids.labels[i] > regions)
      throw InputError("tissue-id image: voxel " + std::to_string(i) + " has id " + std::to_string(ids.labels[i]) +
                       ", expected 0.." + std::to_string(regions));
  SurfaceExtraction out;
  LabelImage work = ids;
  {
    // The repair can cut a thin filament off a tissue (it relabels pinch voxels), leaving a new
    // island, and an absorbed island can leave a pinch: alternate until neither changes anything
    // (the repair only raises ids and each absorption removes an island, so this ends quickly).
    auto stage = progress.stage("absorb islands under " + std::to_string(params.min_island_voxels) +
                                " voxels, repair non-manifold voxel configurations");
    const auto min_voxels = static_cast<std::size_t>(params.min_island_voxels);
    std::vector<std::size_t> repaired;  // the voxels the last repair relabelled
    bool no_islands_before_repair = false;
    for (int round = 0; round < kIslandRounds; ++round) {
      // After a repair, islands can only be where it relabelled (absorb_small_islands' hint).
      const IslandAbsorption islands =
          absorb_small_islands(work, min_voxels, no_islands_before_repair ? &repaired : nullptr);
      no_islands_before_repair = islands.complete;
      out.islands.add(islands);
      if (round > 0 && islands.islands == 0) break;
      const std::vector<std::int32_t> before = work.labels;
      const LabelRepairResult repair = make_well_composed(work);
      out.repair.relabelled_voxels += repair.relabelled_voxels;
      out.repair.passes += repair.passes;
      if (repair.relabelled_voxels == 0) break;
      repaired.clear();
      for (std::size_t v = 0; v < before.size(); ++v)
        if (before[v] != work.labels[v]) repaired.push_back(v);
    }
    stage.note(std::to_string(out.islands.islands) + " islands (" + std::to_string(out.islands.voxels) +
               " voxels) absorbed, " + std::to_string(out.repair.relabelled_voxels) + " voxels relabelled in " +
               std::to_string(out.repair.passes) + " repair passes");
  }
  auto stage = progress.stage("surface nets");
  NetBuilder net(work);
  net.build(work.dims);
  if (net.quads.empty()) throw MeshingError("the tissue-id image has no boundary between regions");
  const std::size_t n = net.lattice.size();

  const auto curve_adj = net.junction_edges();
  std::vector<VertexKind> kind(n, VertexKind::Surface);
  for (std::size_t v = 0; v < n; ++v) {
    if (curve_adj[v].size() == 2) {
      kind[v] = VertexKind::Curve;
      ++out.curve_vertices;
    } else if (!curve_adj[v].empty() || net.regions_around(static_cast<int>(v)) > 2) {
      kind[v] = VertexKind::Corner;
      ++out.corner_vertices;
    }
  }
  // Smoothing shrinks a short closed junction loop (a contact of one or two voxel faces between
  // two tissues inside a third) towards a point, down to a perimeter of a fraction of a millimetre,
  // below anything a volume mesher can resolve without micrometre tets. Such loops keep their
  // voxel corners here, but stay curve vertices of one closed polyline, not corners: corners are
  // fixed in the remesher too, which could then not reshape the voxel-sized triangles between them
  // (a 0.7 x 1.5 mm voxel face gives an angle of atan(0.7 / 1.5) = 25 degrees).
  std::vector<char> pinned(n, 0);
  for (std::size_t v = 0; v < n; ++v) pinned[v] = kind[v] == VertexKind::Corner;
  for (const auto& loop : trace_junctions(curve_adj, kind))
    if (loop.front() == loop.back() && loop.size() <= kShortLoopEdges + 1)
      for (int v : loop) pinned[static_cast<std::size_t>(v)] = 1;
  std::vector<Eigen::Vector3d> x(n);
  for (std::size_t v = 0; v < n; ++v)
    x[v] = Eigen::Vector3d(net.lattice[v][0] - 0.5, net.lattice[v][1] - 0.5, net.lattice[v][2] - 0.5);
  relax(x, net.lattice, kind, pinned, quad_neighbours(n, net.quads), curve_adj, params.relaxation_iterations);

  TriSurface& s = out.surface;
  s.tissue_names = tissue_names;
  s.points.resize(n);
  for (std::size_t v = 0; v < n; ++v) s.points[v] = ids.to_physical(x[v]);
  const bool mirrored = ids.index_to_physical().determinant() < 0.0;
  s.triangles.reserve(2 * net.quads.size());
  s.labels.reserve(2 * net.quads.size());
  for (std::size_t q = 0; q < net.quads.size(); ++q) {
    const auto& c = net.quads[q];
    const auto& P = s.points;
    std::array<std::array<int, 3>, 2> tris;
    if ((P[c[0]] - P[c[2]]).squaredNorm() <= (P[c[1]] - P[c[3]]).squaredNorm())
      tris = {{{c[0], c[1], c[2]}, {c[0], c[2], c[3]}}};
    else
      tris = {{{c[0], c[1], c[3]}, {c[1], c[2], c[3]}}};
    for (auto t : tris) {
      if (mirrored) std::swap(t[1], t[2]);
      s.triangles.push_back(t);
      s.labels.push_back(net.quad_labels[q]);
    }
  }
  s.junctions = trace_junctions(curve_adj, kind);

  // Relaxation can fold the surface where a thin layer bends sharply. Vertices of intersecting
  // triangles go halfway back to their voxel corner, round after round (the unrelaxed voxel
  // boundary of well-composed regions has no intersections); the last round puts them there. After
  // the first, full check each round re-checks only around the vertices it moved.
  std::vector<int> bad;
  out.checks = check_surface(s, &bad, PairSearch::Grid);  // a large surface: the fast search
  for (int round = 0; !bad.empty() && round < kUnfoldRounds; ++round) {
    std::vector<int> moved;
    for (int t : bad)
      for (int v : s.triangles[static_cast<std::size_t>(t)]) moved.push_back(v);
    std::sort(moved.begin(), moved.end());
    moved.erase(std::unique(moved.begin(), moved.end()), moved.end());
    for (int v : moved) {
      const auto& l = net.lattice[static_cast<std::size_t>(v)];
      const Eigen::Vector3d corner(l[0] - 0.5, l[1] - 0.5, l[2] - 0.5);
      x[static_cast<std::size_t>(v)] = round + 1 == kUnfoldRounds ? corner : 0.5 * (x[static_cast<std::size_t>(v)] + corner);
      s.points[static_cast<std::size_t>(v)] = ids.to_physical(x[static_cast<std::size_t>(v)]);
    }
    out.unfolded_vertices += moved.size();
    std::vector<int> still;
    out.checks = recheck_after_moves(s, out.checks, bad, moved, &still);
    bad = std::move(still);
  }
  stage.note(std::to_string(n) + " vertices, " + std::to_string(s.triangles.size()) + " triangles, " +
             std::to_string(s.junctions.size()) + " junction polylines");
  return out;
}

}  // namespace tissuemesh
