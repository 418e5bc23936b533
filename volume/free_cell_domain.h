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
#include "volume/free_cell_grid.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polyhedral_complex_mesh_domain_3.h>
#include <CGAL/point_generators_3.h>

#include <Eigen/Core>

#include <cstddef>
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

 private:
  std::optional<FreeCellGrid> grid_;
  std::vector<Subdomain> regions_;  ///< per grid component
  std::vector<char> known_;         ///< per grid component: its seed's three rays agreed
};

}  // namespace tissuemesh
