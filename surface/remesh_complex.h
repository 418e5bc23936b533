// RemeshComplex: the working mesh of the surface remesher (surface/surface_remesh.h) and its local
// operations on the whole multi-material complex (Botsch & Kobbelt, "A remeshing approach to
// multiresolution modeling", SGP 2004, extended to junction curves), against a size field
// h(x) = L s(x):
//   split     edges longer than 4/3 h at their midpoint, which is projected onto the edge's patch or,
//             for a junction edge, onto its junction polyline (every triangle around it is split),
//             unless a half would turn by more than 154 degrees from the triangle it halves;
//   collapse  edges shorter than 4/5 h when no edge of the result is longer than 4/3 h: a surface
//             vertex into any neighbour across a non-junction edge, a curve vertex only into its
//             neighbour along the same junction; corners (polyline ends, where curves meet) stay;
//             the link condition (the endpoints share exactly the opposite vertices of the edge's
//             triangles) keeps every tissue's boundary a closed manifold;
//   flip      non-junction edges to the Delaunay diagonal of their two triangles (same patch),
//             when the two new triangles do not fold against each other and neither endpoint is
//             left with three triangles;
//   relax     density-weighted centroidal relaxation: a surface vertex moves to the centroid of its
//             one-ring weighted by area / h^2 (a discrete centroidal Voronoi step, Lloyd on the
//             surface), tangentially, then onto its patch of the reference surface; a curve
//             vertex to the weighted midpoint of its two curve neighbours, then onto its junction;
// plus the angle and quality smoothing, removals and splits of the polish (documented below).
// Every operation keeps the patch labels, the orientation and the junction polylines (their
// vertices and edges are replaced along the same curve), and refuses a move that flips a
// triangle. Validity: an operation is refused when one of the triangles it creates would intersect
// another one or any live triangle of the complex (exact predicates, surface/triangle_intersection.h;
// candidates from a grid of triangle boxes, surface/triangle_grid.h), so an intersection-free input
// stays intersection free at any budget. With options.fold_guard, an operation is also refused when
// two triangles of one patch across an edge would turn from each other by more than 154 degrees
// (kFoldCos) and by more than the worst such pair among the triangles it replaces. Shape: each
// vertex carries the input vertices collapsed into it, and a collapse or relaxation move is
// refused when one of them would end up farther than the approximation bound
// (max(max_deviation_mm, L/4), times scale_deviation()'s factor) from the triangles around it (an
// angle- or quality-smoothing move may instead hand it to a neighbour whose triangles are within
// the bound), or when a changed triangle would leave its patch by more than that bound or face
// away from it;
// split midpoints and relaxed points that would project onto the far side of a thin sheet are
// refused too. Size near stuck edges: after grade_stuck_edges(), h(x) = min(L s(x), cap(x)) with
// the GradedSizeCap (surface/graded_size_cap.h) of the edges between two junction vertices that
// stayed far shorter than h.
// Deterministic: every sweep visits triangles and vertices in index order, the partitioned ones
// (collapse_short, relax) each half in index order, the halves on two threads (remesh_partition.cpp).
#pragma once

#include "core/tri_surface.h"
#include "surface/surface_projection.h"
#include "surface/graded_size_cap.h"
#include "surface/surface_remesh.h"
#include "surface/triangle_grid.h"
#include "surface/triangle_intersection.h"

#include <Eigen/Core>

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <unordered_map>
#include <vector>

namespace tissuemesh {

class RemeshComplex {
 public:
  /// `in` is the reference surface (valid, closed per tissue); `projection` is built on it and
  /// must outlive this object. Takes options.relative_size, options.max_edge_mm,
  /// options.max_deviation_mm and options.threads.
  RemeshComplex(const TriSurface& in, const SurfaceProjection& projection, const RemeshOptions& options);

  double L = 1.0;  ///< edge length where s = 1, mm
  std::size_t splits = 0, collapses = 0, flips = 0;
  std::size_t partitioned_sweeps = 0;  ///< sweeps run as two halves
  std::size_t skipped_collapse_tries = 0;  ///< edges collapse_until_stable's later sweeps did not try again

  std::size_t vertices() const { return alive_vertices_; }
  /// Live vertices that never move or go (junction corners, pinches).
  std::size_t corners() const;
  /// What no coarsening can remove: the corners, kMinLoopEdges vertices on every closed junction
  /// curve, and 4 vertices (a tetrahedron) for every closed piece of surface with no junction on
  /// it (an island inside one tissue). A budget below total() cannot be met.
  struct VertexFloor {
    std::size_t corners = 0, closed_curves = 0, closed_pieces = 0;
    std::size_t loop_vertices = 0;  ///< per closed curve
    std::size_t total() const { return corners + loop_vertices * closed_curves + 4 * closed_pieces; }
  };
  VertexFloor vertex_floor() const;
  /// Integral of 1 / s^2 over the surface (each triangle once), mm^2.
  double weighted_area() const;
  /// Vertices the thin parts ask for at edge length L: the integral of 2 / (sqrt(3) b^2) over the
  /// triangles where options.max_edge_mm (times thickness_scale) b is under L (0 without it).
  double thin_vertex_demand() const;
  /// Factor (>= 1) on options.max_edge_mm: thin parts coarsened to fit a budget (+infinity: no bound).
  double thickness_scale = 1.0;

  // Sweeps over all edges (or vertices), in index order; each returns how many operations it did.
  // collapse_short and relax are partitioned sweeps on a large complex (remesh_partition.cpp):
  // the edges (vertices) of either half of the complex, in index order, the two halves on two
  // threads at once, then in index order those of the band between the halves. Their results do
  // not depend on the number of threads.
  std::size_t split_long();
  std::size_t collapse_short() { return collapse_sweep(false); }
  /// collapse_short() and compact() until a sweep collapses nothing, at most `max_sweeps` sweeps;
  /// returns the collapses. A sweep after the first does not try an edge again when neither of its
  /// vertices had its ring changed (by a collapse, or an intersection guard refusing one of its
  /// collapses) since the previous sweep began: every test of a collapse but the intersection
  /// guard reads only the two rings and what stays fixed between these sweeps (sizes, bound,
  /// reference, kinds), besides the junction edge counts, which only fall (a refusal for a short
  /// junction stands). So that sweep's refusal stands, and the result is the one of trying every
  /// edge again.
  std::size_t collapse_until_stable(int max_sweeps);
  /// flip_all first runs the local tests of every edge's flip on two threads and then, in index
  /// order, tries only the edges they did not refuse or whose neighbourhood a flip has changed
  /// since; `skip_refused` false tries every edge (the sweep it must equal, for the tests).
  std::size_t flip_all(bool skip_refused = true);
  void relax();

  /// Angle-improving smoothing of the vertices of triangles with an angle under `min_angle_rad`:
  /// each moves towards the mean of its neighbours (or halfway, or a quarter), onto its patch or
  /// junction, when that raises the smallest angle around it; a vertex for which none does gets a
  /// pattern search over its patch (or along its junction) for the position with the largest
  /// smallest angle (search_min_angle). Appends the vertices it moved to `moved`.
  void smooth_poor(double min_angle_rad, std::vector<int>& moved);
  /// Quality-raising smoothing of the surface vertices of triangles whose Frey-Borouchaki quality
  /// (surface/triangle_geometry.h) is under `q_below`: the pattern search of search_min_angle
  /// (search_on_patch) for the position with the largest smallest quality around the vertex,
  /// among positions that keep its smallest angle at least min(its current one, `min_angle_rad`)
  /// and do not raise its count of angles under `min_angle_rad`; the vertex moves there if that
  /// raises its smallest quality and try_move's guards allow it (input vertices it stands for may
  /// be handed to a neighbour, as in smooth_poor). So the surface's Q_min never drops, its count
  /// of angles under `min_angle_rad` never grows, and its smallest angle never drops below
  /// min(its current value, `min_angle_rad`). Appends the vertices it moved to `moved`.
  void smooth_low_quality(double q_below, double min_angle_rad, std::vector<int>& moved);
  /// Mean-quality smoothing of the surface vertices of triangles whose quality is under
  /// `q_below`: the same pattern search for the position with the largest sum of the qualities of
  /// the vertex's triangles, among positions that keep their smallest angle at least min(its
  /// current one, `angle_floor_rad`), do not raise their count of angles under `min_angle_rad`,
  /// and keep their smallest quality at least min(its current one, `q_floor`); the vertex moves
  /// there if that raises the sum and try_move's guards allow it. So the surface's count of angles
  /// under `min_angle_rad` never grows, its smallest angle never drops below min(its value,
  /// `angle_floor_rad`) nor its Q_min below min(its value, `q_floor`), while the mean quality (and
  /// with it the mean smallest angle) rises. Appends the vertices it moved to `moved`.
  void smooth_mean_quality(double q_below, double min_angle_rad, double angle_floor_rad, double q_floor,
                           std::vector<int>& moved);
  /// Tries the flip of every edge of the triangles around `vertices` (after they moved: only those
  /// triangles' angles changed, so only their edges can have become flippable); returns the flips.
  std::size_t flip_around(const std::vector<int>& vertices);
  /// Removes each surface vertex of at most four triangles, one of them with an angle under
  /// `min_angle_rad`, by collapsing it into the neighbour that leaves the largest smallest angle,
  /// when that beats the smallest angle of its triangles now and the collapse's guards allow it
  /// (a vertex of three triangles in a flat patch has ~120 degrees in each, so each of them has
  /// an angle of 30 degrees or less beside it, whatever the vertex's position); returns the
  /// removals. The caller restores the vertex budget.
  std::size_t collapse_poor(double min_angle_rad);
  /// Splits the longest edge of each triangle with an angle under `min_angle_rad` when the
  /// triangles the split makes all have a larger smallest angle than the ones it replaces (a poor
  /// triangle whose short edge no move can lengthen, e.g. one held by the approximation bound);
  /// returns the splits and appends the new vertices to `added`.
  std::size_t split_poor(double min_angle_rad, std::vector<int>& added);

  /// Drops dead vertices and triangles (the coarsening kills most of them), renumbering the live
  /// ones in their order: every sweep then walks short arrays, and since all index comparisons
  /// keep their outcome, the results do not change (surface/remesh_compact.cpp).
  void compact();

  /// Enters every edge between two junction vertices that is shorter than `below` times h at its
  /// midpoint into the size cap (header comment); edges entered before stay. Call once the
  /// collapses have converged, so that the short edges left are the ones the corners and guards
  /// keep.
  void grade_stuck_edges(double below);
  /// Enters the shortest edge of every triangle with an angle under `min_angle_rad` into the size
  /// cap (its length at its midpoint, reaching up to 2 L), so that the next rounds remesh finer
  /// around what the polish could not fix. Returns the triangles entered.
  std::size_t cap_poor_triangles(double min_angle_rad);
  /// Limits the sweeps (split_long, collapse_short, flip_all, relax) to edges whose midpoint, and
  /// vertices that lie, within `radius` (mm) of the centroid of a triangle with an angle under
  /// `min_angle_rad` now: a repair that remeshes around the poor triangles and leaves the rest
  /// as it is. unfocus() lifts the limit.
  void focus_on_poor_triangles(double min_angle_rad, double radius);
  void unfocus() { focus_.clear(); }
  /// Multiplies the approximation bound (deviation(), > 0) from now on; 1 restores it.
  void scale_deviation(double factor) { deviation_scale_ = factor; }
  /// The step by which the approximation bound is loosened where it holds vertices in place: per
  /// stuck round of match_count, and per repair attempt (surface/surface_remesh.cpp).
  static constexpr double kDeviationLoosening = 1.5;

  /// Collapses the relatively shortest or splits the relatively longest edges until the vertex
  /// count is `target`; false when it cannot get there (every candidate refused, even with the
  /// approximation bound loosened by kDeviationLoosening per stuck round).
  bool match_count(std::size_t target);

  /// The live mesh, compacted, with its junction polylines chained again (labels and tissue names
  /// from `in`). Throws MeshingError if a junction no longer forms one polyline (a bug).
  TriSurface result(const TriSurface& in) const;

 private:
  using Vector3d = Eigen::Vector3d;
  enum class Kind : char { Surface, Curve, Corner };

  /// A collapse, flip or relaxation move is refused when a triangle's normal turns by more than
  /// this (cos 60 deg): it would fold the surface or leave the reference shape's tangent plane.
  static constexpr double kMinNormalTurnCos = 0.5;
  /// A closed junction loop keeps at least this many edges. Three would do topologically, but a
  /// loop only a few voxel faces long (a sub-resolution contact, kept at its voxel corners by the
  /// extraction) then becomes one triangle inscribed in a rectangle, obtuse with two angles under
  /// 30 degrees (e.g. 29, 29 and 122 degrees on a 1.4 x 1.5 mm contact); four vertices evenly
  /// spaced along it make a near-square of two near-right triangles.
  static constexpr int kMinLoopEdges = 4;

  /// The approximation bound in force: the caller's floor, or a quarter of the edge length when
  /// that is larger (a coarse budget cannot follow the surface to within a voxel); grown by
  /// match_count when the budget cannot be met otherwise.
  double deviation() const;
  /// h(p) / L: the caller's relative size, lowered by the size cap.
  double s(const Vector3d& p) const;
  double h(const Vector3d& p) const { return L * s(p); }
  /// Length of edge (a, b) relative to h at its midpoint.
  double relative_length(int a, int b) const { return (x_[a] - x_[b]).norm() / h(0.5 * (x_[a] + x_[b])); }

  /// Edges (a < b) of the live triangles, in triangle order (deterministic).
  std::vector<std::array<int, 2>> edges() const;
  bool has(int t, int v) const { return tri_[t][0] == v || tri_[t][1] == v || tri_[t][2] == v; }
  bool edge_exists(int a, int b) const;
  void edge_triangles(int a, int b, std::vector<int>& out) const;
  void neighbours(int v, std::vector<int>& out) const;
  int curve_of_edge(int a, int b) const;  ///< -1 for a non-junction edge
  Vector3d normal(int t) const;
  /// Normal of triangle t with vertex `v` moved to `p`.
  Vector3d moved_normal(int t, int v, const Vector3d& p) const;
  /// True when moving v to p turns no triangle of `tris` (skipping `skip`) beyond the limit.
  bool move_keeps_normals(int v, const Vector3d& p, const std::vector<int>& tris, const std::vector<int>& skip) const;
  /// True when every input vertex that v stands for stays within deviation() of v's triangles
  /// with v moved to p (relaxation must not shave off a tip that collapses left to v). With
  /// `handoff`, an input vertex out of v's reach may instead be within deviation() of a
  /// neighbour w's triangles (v at p): it is listed as {input vertex, w}, for try_move to hand
  /// it over, so that every input vertex stays within reach of its own vertex's triangles.
  bool keeps_represented(int v, const Vector3d& p, std::vector<std::array<int, 2>>* handoff = nullptr) const;
  /// Distance from input vertex r to w's triangles with vertex v moved to p.
  double ring_distance(int r, int w, int v, const Vector3d& p) const;

  /// A triangle an operation would create: vertex ids (a new vertex: an id not yet in use) and points.
  struct NewTriangle {
    std::array<int, 3> v;
    TrianglePoints p;
    int patch = -1;  ///< the patch of the triangle it replaces
  };
  /// With options.fold_guard, two triangles of one patch across an edge may turn from each other
  /// by at most acos(kFoldCos) = 154 degrees (the split's kSplitFoldCos), or by no more than the
  /// worst such pair among the triangles an operation replaces: the extracted surface has no
  /// wedge under 30 degrees, but coarsening a fold or fin thinner than the edges, and the angle
  /// smoothing, can flatten it almost completely, and a tet filling such a wedge is as flat.
  static constexpr double kFoldCos = -0.9;
  /// Smallest cosine between the normals of two triangles of one patch that share an edge: over
  /// the edges of created_ after the operation (against each other and against the live
  /// triangles not in `replaced`), or over the edges of the live triangles `replaced` before it.
  double fold_cos_after(const std::vector<int>& replaced);
  double fold_cos_before(const std::vector<int>& replaced) const;
  /// options.fold_guard and the operation replacing `replaced` by created_ folds beyond kFoldCos
  /// and beyond what it replaces.
  bool would_fold(const std::vector<int>& replaced);
  /// Live triangles with an angle under `min_angle_rad`, in index order.
  std::vector<int> poor_triangles(double min_angle_rad) const;
  /// Position i in q of its longest (else shortest) edge (q[i], q[(i + 1) % 3]); ties: the first.
  int extreme_edge(const std::array<int, 3>& q, bool longest) const;
  /// Triangle t with vertex v moved to p and renamed `id`.
  NewTriangle moved_triangle(int t, int v, const Vector3d& p, int id) const;
  /// Fills created_ with the triangles of `tris` (skipping `skip`) with v moved to p, renamed id.
  void collect_moved(const std::vector<int>& tris, const std::vector<int>& skip, int v, const Vector3d& p, int id);
  /// True when a triangle of created_ would intersect another of them or a live triangle not in
  /// `replaced` (the ones the operation removes or changes).
  bool would_intersect(const std::vector<int>& replaced);
  /// Area-weighted unit normal of v's triangles; zero when they have none.
  Vector3d vertex_normal(int v) const;
  /// Where a surface vertex v moving towards `goal` lands: the tangential part of the move (in
  /// the plane of v's normal `n`, vertex_normal(v)) projected onto v's patch; false when v's
  /// triangles have no normal or the projection lands on the far side of a thin sheet.
  bool tangential_target(int v, const Vector3d& n, const Vector3d& goal, Vector3d& target) const;
  bool tangential_target(int v, const Vector3d& goal, Vector3d& target) const {
    return tangential_target(v, vertex_normal(v), goal, target);
  }
  /// One vertex of relax(): moves it towards its weighted centroid (header comment). `side`: the
  /// half of a partitioned sweep it is visited in (-1: the band, or no partition). Returns 1 when
  /// it moved, 0 when not, -1 when the move would touch the other half or the band (then the
  /// band visits it again).
  int relax_vertex(int v, int side);
  /// One edge of collapse_short(), with `side` and the result as in relax_vertex.
  int collapse_edge(int a, int b, int side);
  /// Partitioned sweeps: sets side_ (every vertex -1 when the complex is too small to split) and
  /// returns whether there are two halves. A half is the vertices whose grid slab across the split
  /// axis is below (side 0) or above (side 1) band_slab_, the median one.
  bool assign_sides();
  /// v and every vertex of v's triangles are on `side` (an operation at v touches nothing else).
  bool vertex_on_side(int v, int side) const;
  /// p's grid slab belongs to `side`.
  bool point_on_side(const Vector3d& p, int side) const;
  /// Applies op(item, side) (relax_vertex or collapse_edge) to `items` as a partitioned sweep:
  /// with two halves, those with side_of(item) 0 or 1 on their half's thread, then every item
  /// not yet done (op returned -1, or side -1) in order with side -1. Returns the 1s.
  template <class Item, class SideOf, class Op>
  std::size_t partitioned_sweep(const std::vector<Item>& items, SideOf side_of, Op op);
  /// Moves v to p if the normal, shape and intersection guards allow it (header comment).
  /// `handoff`: input vertices v stands for may pass to a neighbour (keeps_represented); the
  /// angle and quality smoothing allow it, so that a vertex next to a junction can move away from it.
  bool try_move(int v, const Vector3d& p, bool handoff = false);
  /// Rebuilds the grid if needed and applies `operation(a, b)` (true: it changed the mesh) to
  /// every edge that still exists, in edges() order; returns how many changed it.
  template <class EdgeOperation>
  std::size_t sweep_edges(EdgeOperation operation);
  /// Surface vertex v: a pattern search over its patch (tangent steps from the best point so far,
  /// each projected onto the patch) for the position with the largest smallest ring angle; curve
  /// vertex v: the same along its junction (steps towards either curve neighbour); moves there if
  /// that beats the current one and the guards of try_move allow it. `nb`: v's neighbours.
  bool search_min_angle(int v, const std::vector<int>& nb);
  /// The pattern search over surface vertex v's patch shared by search_min_angle and
  /// smooth_low_quality: from v's position, steps of `step`, halved kSearchLevels - 1 times, in
  /// eight tangent directions from the best point so far, each landing point projected onto the
  /// patch; returns the point with the largest score(p) (v's own position unless one beats it) and
  /// that score in `best_score`. False when v has no normal (nothing searched).
  template <class Score>
  bool search_on_patch(int v, double step, Score score, Vector3d& best, double& best_score) const;
  /// The vertex loop of smooth_low_quality and smooth_mean_quality: every surface vertex of a
  /// triangle with a quality under `q_below`, in index order, searched over its patch
  /// (search_on_patch) for the largest objective(now, there) (now: its RingShape where it is,
  /// there: at the point tried; a negative value refuses the point), and moved there when that
  /// beats objective(now, now) and try_move (with hand-over) allows it; appended to `moved`.
  template <class Objective>
  void search_low_quality_vertices(double q_below, double min_angle_rad, Objective objective, std::vector<int>& moved);
  /// Smallest angle of v's triangles with v at p (radians).
  double ring_min_angle(int v, const Vector3d& p) const;
  /// v's triangles with v at p: smallest angle (radians), smallest and summed Frey-Borouchaki
  /// quality, and how many of their angles are under `poor_angle_rad`.
  struct RingShape {
    double min_angle;
    double min_quality;
    int poor_angles;
    double quality_sum;
  };
  RingShape ring_shape(int v, const Vector3d& p, double poor_angle_rad) const;
  /// Live triangles (a, b, c) for which bad(a, b, c) holds, in index order.
  template <class Bad>
  std::vector<int> triangles_where(Bad bad) const;
  /// Marks (1) the vertices of `triangles`.
  std::vector<char> vertices_of(const std::vector<int>& triangles) const;
  /// Shorter of the two junction edges at curve vertex v with v at p (mm). Curve moves must not
  /// shorten it: projecting midpoints onto a junction loop smaller than h otherwise pulls the
  /// loop's vertices together (Laplacian shrinkage), down to micrometre edges that a volume
  /// mesher must then resolve.
  double shorter_curve_edge(int v, const Vector3d& p) const;
  /// Enters triangle t's current box in the grid (after it was created or changed).
  void index_triangle(int t);
  /// Start of every sweep (and end of compact()): rebuilds the grid when the triangle size has
  /// drifted from its cells, or when it has none (grid_cell_ 0).
  void rebuild_grid();

  /// Where a split of edge (a, b) (triangles `ts`) puts the new vertex: its midpoint projected onto
  /// the edge's junction or patch; false when it would land on the far side of a thin sheet.
  bool split_point(int a, int b, const std::vector<int>& ts, Vector3d& m) const;
  /// Splits edge (a, b) at split_point(); false (nothing changed) when that is refused or a new
  /// triangle would intersect.
  bool split(int a, int b);
  /// May vertex a be removed by moving it onto b (topology and kinds only)? `ts`: the edge's
  /// triangles, `na`: a's neighbours.
  bool collapse_allowed(int a, int b, const std::vector<int>& ts, const std::vector<int>& na) const;
  /// Collapses a into b if allowed and geometrically sound; `max_relative` bounds the new edges.
  bool try_collapse(int a, int b, double max_relative);
  /// Removes the lower-ranked vertex of (a, b) (surface before curve, then the higher index), or
  /// the other when that is refused.
  bool collapse_either(int a, int b, double max_relative);
  /// A flip of edge (a, b): t1 holds the directed edge a -> b, t2 the edge b -> a, c and d are
  /// their third vertices (-1 until known).
  struct FlipQuad {
    int a = -1, b = -1, c = -1, d = -1, t1 = -1, t2 = -1;
  };
  /// try_flip's tests but the intersection guard: they read only the edge's two triangles, the
  /// triangle lists of a, b and c, and the four points. False when they refuse the flip; `quad` is
  /// filled as far as the tests got (c and d once found).
  bool flip_passes_local_tests(int a, int b, FlipQuad& quad) const;
  /// Flips edge (a, b) when flip_passes_local_tests and the intersection guard allow it; the
  /// flipped quad in `flipped` (old diagonal a, b; new c, d).
  bool try_flip(int a, int b, FlipQuad* flipped = nullptr);

  const SurfaceProjection& proj_;
  std::function<double(const Vector3d&)> size_;
  std::function<double(const Vector3d&)> max_edge_;
  Eigen::AlignedBox3d region_;  ///< the input's bounding box, widened: the grids cover it
  GradedSizeCap cap_;
  double max_deviation_ = 0.0;
  double slack_ = 1.0;  ///< deviation() multiplier, raised by match_count when stuck
  double deviation_scale_ = 1.0;  ///< deviation() multiplier set by scale_deviation()
  bool fold_guard_ = false;       ///< options.fold_guard
  std::vector<Vector3d> reference_;             ///< the input vertices
  std::vector<std::vector<int>> represents_;    ///< per vertex: input vertices collapsed into it
  TriangleGrid grid_;
  /// Per triangle: its bounding box when last entered into grid_ (index_triangle; every change of a
  /// triangle or its vertices re-enters it, and compact() forces a full rebuild).
  std::vector<Eigen::AlignedBox3d> tri_box_;
  double grid_cell_ = 0.0;      ///< the grid's cell size (0: not built yet, or ids renumbered)
  /// The guards' scratch, one per thread of a partitioned sweep (entry 0 serves every sequential
  /// operation too); scratch() picks the calling thread's.
  struct Scratch {
    std::vector<NewTriangle> created;  ///< the triangles an operation would create
    std::vector<Eigen::AlignedBox3d> created_boxes;  ///< would_intersect(): boxes of `created`
    std::vector<PreparedTriangle> created_prepared;  ///< would_intersect(): `created`, prepared
    std::vector<unsigned> seen;  ///< per triangle: stamp of the last would_intersect() visit
    unsigned stamp = 0;
    std::vector<int> candidates;
    std::size_t collapsed = 0;  ///< collapses of a partitioned sweep's half, not yet counted
    std::size_t skipped = 0;    ///< edges a repeated collapse sweep did not try, not yet counted
  };
  std::array<Scratch, 2> scratch_;
  Scratch& scratch();
  /// Where the sweeps act (focus_on_poor_triangles; empty: everywhere) and whether p is there.
  std::vector<Vector3d> focus_;
  double focus_radius_ = 0.0;
  bool in_focus(const Vector3d& p) const;
  /// Partitioned sweeps (surface/remesh_partition.cpp): per vertex, the half of the complex it was
  /// in when the sweep began (0 or 1, -1 the band between them), the grid slab of the band, and
  /// the threads to run the halves on.
  std::vector<signed char> side_;
  int band_slab_ = 0;
  int threads_ = 2;
  bool halves_running_ = false;  ///< inside a partitioned sweep's halves: collapses are counted in scratch()
  /// A collapse sweep; `repeat`: collapse_until_stable's sweep after its first (header comment
  /// there), which skips the edges whose ends' rings did not change.
  std::size_t collapse_sweep(bool repeat);
  /// Collapse sweeps: per vertex, whether its ring changed or a guard refused one of its
  /// collapses in this sweep so far (`ring_changed_`) and in the previous one
  /// (`ring_changed_before_`); marked by try_collapse while `tracking_rings_`. A partitioned
  /// sweep's half marks only vertices on its side (those of the triangles it changes).
  std::vector<char> ring_changed_, ring_changed_before_;
  bool tracking_rings_ = false;
  bool ring_changed(int v) const { return ring_changed_before_[v] || ring_changed_[v]; }
  std::vector<Vector3d> x_;
  std::vector<Kind> kind_;
  std::vector<int> owner_;  ///< patch (surface vertex), curve (curve vertex), -1 (corner)
  std::vector<char> vertex_alive_;
  std::vector<std::array<int, 3>> tri_;
  std::vector<int> patch_;
  std::vector<char> tri_alive_;
  std::vector<std::vector<int>> vt_;
  std::unordered_map<std::uint64_t, int> curve_edge_;
  std::vector<int> curve_edges_;
  std::vector<char> curve_closed_;
  std::size_t alive_vertices_ = 0;
};

}  // namespace tissuemesh
