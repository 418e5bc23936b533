// FreeCellDomain: CGAL's Polyhedral_complex_mesh_domain_3 with its region and surface-intersection
// queries answered from a FreeCellGrid (volume/free_cell_grid.h) away from the surface; the
// volume mesher's domain (volume/complex_mesher.cpp). CGAL-heavy: include only in CGAL
// translation units (complex_mesher.cpp and its test).
//
// The base domain tells which tissue a point is in by shooting a ray in a random direction to the
// first surface triangle it meets. Here each grid component's seed is classified once, by three
// rays (valid for a closed, consistently labelled complex, what mesh_complex is given); a
// component whose rays disagree (a ray grazing an edge) is left to the rays of every query.
// CGAL's random sequence is kept: the seeds' rays run between a saved and a restored state, and
// the fast path draws the direction the base would have drawn, so the meshes are bit-identical to
// the base domain's (the base draws again only for a ray exactly in a triangle's plane or hitting
// nothing identifiable, which a point in a free cell does not meet in practice).
#pragma once

#include "core/tri_surface.h"
#include "surface/box_grid.h"
#include "volume/free_cell_grid.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polyhedral_complex_mesh_domain_3.h>
#include <CGAL/point_generators_3.h>

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <type_traits>
#include <utility>
#include <vector>

namespace tissuemesh {

using ComplexDomain = CGAL::Polyhedral_complex_mesh_domain_3<CGAL::Epick>;

class FreeCellDomain : public ComplexDomain {
 public:
  using ComplexDomain::ComplexDomain;

  /// Builds the grid over `surface` (the triangles of the polyhedra) with cells of `cell_mm` and
  /// classifies its components; returns the grid and the components left to the rays.
  std::pair<const FreeCellGrid*, std::size_t> index_regions(const TriSurface& surface, double cell_mm) {
    grid_.emplace(surface.points, surface.triangles, cell_mm);
    CGAL::Random::State state;
    CGAL::get_default_random().save_state(state);
    const ComplexDomain::Is_in_domain shoot(*this);
    regions_.clear();
    known_.clear();
    std::size_t unknown = 0;
    for (std::size_t c = 0; c < grid_->components(); ++c) {
      const Eigen::Vector3d& x = grid_->seed(c);
      const Point_3 seed(x[0], x[1], x[2]);
      const Subdomain first = shoot(seed);
      const bool agree = shoot(seed) == first && shoot(seed) == first;
      regions_.push_back(first);
      known_.push_back(agree);
      unknown += !agree;
    }
    CGAL::get_default_random().restore_state(state);
    return {&*grid_, unknown};
  }

  struct Is_in_domain {
    const FreeCellDomain& domain;
    Subdomain operator()(const Point_3& p) const {
      // Outside the tree's box CGAL answers "outside" without drawing a direction; the grid's
      // border cells reach beyond that box, so they must not take the drawing path.
      const CGAL::Bbox_3& box = domain.bounding_aabb_tree_ptr()->bbox();
      const bool inside_box = p.x() >= box.xmin() && p.x() <= box.xmax() && p.y() >= box.ymin() &&
                              p.y() <= box.ymax() && p.z() >= box.zmin() && p.z() <= box.zmax();
      const int c = inside_box && domain.grid_ ? domain.grid_->component(Eigen::Vector3d(p.x(), p.y(), p.z())) : -1;
      if (c < 0 || !domain.known_[static_cast<std::size_t>(c)]) return ComplexDomain::Is_in_domain(domain)(p);
      CGAL::Random_points_on_sphere_3<Point_3> unused_direction(1.);
      return domain.regions_[c];
    }
  };
  Is_in_domain is_in_domain_object() const { return Is_in_domain{*this}; }

  // The surface intersection of a facet's dual segment: none when the segment only crosses free
  // cells (no triangle there), which CGAL's tree search would also find, only slower.
  struct Construct_intersection {
    const FreeCellDomain& domain;
    template <class Query>
    Intersection operator()(const Query& q) const {
      if constexpr (std::is_same_v<Query, Segment_3>) {
        const Point_3& a = q.source();
        const Point_3& b = q.target();
        if (domain.grid_ && domain.grid_->segment_is_free(Eigen::Vector3d(a.x(), a.y(), a.z()),
                                                          Eigen::Vector3d(b.x(), b.y(), b.z())))
          return Intersection();
      }
      return ComplexDomain::Construct_intersection(domain)(q);
    }
  };
  Construct_intersection construct_intersection_object() const { return Construct_intersection{*this}; }

  /// CGAL's add_vertices_to_c3t3_on_patch_without_feature_edges (the same points, drawn from the
  /// same random sequence): up to 20 polyhedron vertices per patch outside every protecting ball
  /// are sampled; a closed patch gets all of its samples as surface vertices, a patch with feature
  /// edges the one farthest from its nearest power vertex. "Outside every ball" is CGAL's test
  /// (the nearest power vertex's ball does not hold the point, which is the case exactly when no
  /// ball holds it), asked here of the balls listed in the point's cell of a grid of their boxes
  /// instead of by a walk through the triangulation for each of the polyhedra's vertices.
  template <class C3t3>
  void add_patch_seeds(C3t3& c3t3) const {
    using Tr = typename C3t3::Triangulation;
    using Vertex = typename Polyhedron::Vertex_const_handle;
    Tr& tr = c3t3.triangulation();
    const auto cw = tr.geom_traits().compute_weight_3_object();
    const auto cp = tr.geom_traits().construct_point_3_object();
    const auto cwp = tr.geom_traits().construct_weighted_point_3_object();
    const BallGrid balls(tr, cp, cw);
    CGAL::Random random(0);
    const std::size_t patches = this->nb_of_patch_plus_one();
    constexpr std::size_t kPerPatch = 20;
    std::vector<std::size_t> free_on_patch(patches, 0);
    for (const Polyhedron& p : this->polyhedra())
      for (auto v = p.vertices_begin(); v != p.vertices_end(); ++v)
        if (!v->is_feature_vertex() && !balls.holds(v->point())) ++free_on_patch[v->halfedge()->face()->patch_id()];
    std::vector<std::size_t> needed(patches);
    for (std::size_t i = 0; i < patches; ++i) needed[i] = std::min(kPerPatch, free_on_patch[i]);
    std::vector<std::vector<Vertex>> samples(patches);
    for (const Polyhedron& p : this->polyhedra())
      for (auto v = p.vertices_begin(); v != p.vertices_end(); ++v) {
        if (v->is_feature_vertex()) continue;
        const std::size_t patch = static_cast<std::size_t>(v->halfedge()->face()->patch_id());
        if (needed[patch] == 0 || balls.holds(v->point())) continue;
        // SGI's random_sample_n, as in CGAL.
        if (random.uniform_smallint(std::uint32_t(0), std::uint32_t(free_on_patch[patch])) < std::uint32_t(needed[patch])) {
          samples[patch].push_back(v);
          --needed[patch];
        }
        --free_on_patch[patch];
      }
    for (std::size_t patch = 1; patch < patches; ++patch) {
      std::vector<Vertex> inserted;
      if (!this->patch_has_featured_edges.test(patch)) {
        inserted = samples[patch];
      } else if (!samples[patch].empty()) {
        auto gap = [&](Vertex v) { return CGAL::squared_distance(v->point(), tr.point(tr.nearest_power_vertex(v->point())).point()); };
        Vertex far = samples[patch].front();
        double far_gap = gap(far);
        for (std::size_t i = 1; i < samples[patch].size(); ++i)
          if (const double g = gap(samples[patch][i]); g > far_gap) {
            far = samples[patch][i];
            far_gap = g;
          }
        inserted = {far};
      }
      for (const Vertex& v : inserted) {
        const auto tv = tr.insert(cwp(v->point()));
        c3t3.set_dimension(tv, 2);
        c3t3.set_index(tv, static_cast<Patch_id>(patch));
      }
    }
  }

 private:
  // The triangulation's vertices as balls (centre, squared radius = weight), each listed in the
  // cells of a BoxGrid that its bounding box (padded against round-off) touches.
  class BallGrid {
   public:
    template <class Tr, class CP, class CW>
    BallGrid(const Tr& tr, const CP& cp, const CW& cw) : cells_(boxes(tr, cp, cw)) {}
    /// True when a ball holds p (on or inside its sphere).
    bool holds(const Point_3& p) const {
      const std::int64_t c = cells_.index(cells_.cell_of(Eigen::Vector3d(p.x(), p.y(), p.z())));
      return std::any_of(cells_.begin(c), cells_.end(c), [&](int b) { return !balls_[b].has_on_unbounded_side(p); });
    }

   private:
    template <class Tr, class CP, class CW>
    BoxGrid boxes(const Tr& tr, const CP& cp, const CW& cw) {
      std::vector<Eigen::Vector3d> lo, hi;
      for (auto v = tr.finite_vertices_begin(); v != tr.finite_vertices_end(); ++v) {
        const auto& wp = tr.point(v);
        balls_.emplace_back(cp(wp), cw(wp));
        const Point_3& c = balls_.back().center();
        const double r = std::sqrt(std::max(0.0, balls_.back().squared_radius())) * (1 + 1e-9) + 1e-9;
        lo.emplace_back(c.x() - r, c.y() - r, c.z() - r);
        hi.emplace_back(c.x() + r, c.y() + r, c.z() + r);
      }
      return BoxGrid(lo, hi, {}, 1.0);
    }
    std::vector<CGAL::Epick::Sphere_3> balls_;
    BoxGrid cells_;
  };

  std::optional<FreeCellGrid> grid_;
  std::vector<Subdomain> regions_;  ///< per grid component
  std::vector<char> known_;         ///< per grid component: its seed's three rays agreed
};

}  // namespace tissuemesh
