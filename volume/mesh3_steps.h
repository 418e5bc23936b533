// The steps every CGAL Mesh_3 run of tissuemesh ends with, shared by the direct pipeline
// (direct_mesher.cpp) and the volume mesher of the surface pipeline (complex_mesher.cpp): the
// optimisers of Mesh3Optimisation, then the cells of the complex as a TetMesh. Templates over the
// C3t3 and domain types, so include this only in those CGAL translation units.
#pragma once

#include "core/errors.h"
#include "core/progress.h"
#include "core/tet_mesh.h"
#include "volume/mesh3_optimisation.h"

#include <CGAL/make_mesh_3.h>
#include <CGAL/optimize_mesh_3.h>

#include <Eigen/Core>

#include <unordered_map>
#include <string>
#include <utility>
#include <vector>

namespace tissuemesh::mesh3 {

/// Delaunay refinement of an initialised complex (protecting balls and seeds in place) to
/// `criteria`, as a progress stage noting the tet count; optimisation is left to optimise().
template <class C3t3, class Domain, class Criteria>
void refine(C3t3& c3t3, const Domain& domain, const Criteria& criteria, Progress& progress) {
  namespace p = CGAL::parameters;
  auto stage = progress.stage("refine (CGAL Mesh_3)");
  CGAL::refine_mesh_3(c3t3, domain, criteria, p::no_perturb(), p::no_exude());
  stage.note(std::to_string(c3t3.number_of_cells_in_complex()) + " tets");
}

/// Lloyd, ODT, perturbation and exudation as `o` asks, each a progress stage; a step stopped by
/// its time limit adds a warning (its result then depends on machine speed).
template <class C3t3, class Domain>
void optimise(C3t3& c3t3, const Domain& domain, const Mesh3Optimisation& o, Progress& progress,
              std::vector<std::string>& warnings) {
  namespace p = CGAL::parameters;
  auto note_time_limit = [&](const std::string& what, CGAL::Mesh_optimization_return_code code) {
    if (code == CGAL::TIME_LIMIT_REACHED)
      warnings.push_back(what + " stopped at its time limit: the mesh depends on machine speed and "
                                "may differ between runs (raise the limit or lower sliver_bound_deg)");
  };
  if (o.lloyd) {
    auto stage = progress.stage("Lloyd");
    note_time_limit("Lloyd", CGAL::lloyd_optimize_mesh_3(c3t3, domain, p::time_limit = o.optimise_time_limit_s));
  }
  if (o.odt) {
    auto stage = progress.stage("ODT");
    note_time_limit("ODT", CGAL::odt_optimize_mesh_3(c3t3, domain, p::time_limit = o.optimise_time_limit_s));
  }
  if (o.perturb) {
    auto stage = progress.stage("perturb slivers");
    note_time_limit("perturbation", CGAL::perturb_mesh_3(c3t3, domain, p::time_limit = o.sliver_time_limit_s,
                                                         p::sliver_bound = o.sliver_bound_deg));
  }
  if (o.exude) {
    auto stage = progress.stage("exude slivers");
    note_time_limit("exudation", CGAL::exude_mesh_3(c3t3, p::time_limit = o.sliver_time_limit_s,
                                                    p::sliver_bound = o.sliver_bound_deg));
  }
}

/// The cells of the complex, nodes numbered in order of first use (deterministic), each point
/// mapped by `to_physical(x, y, z)` -> Eigen::Vector3d; the subdomain index is the tissue id.
/// CGAL cells are positively oriented in CGAL's frame; `reflect` (a mapping with negative
/// determinant) swaps two nodes so they stay positive. Throws MeshingError for an empty complex.
template <class C3t3, class ToPhysical>
TetMesh cells(const C3t3& c3t3, const ToPhysical& to_physical, bool reflect, const std::vector<std::string>& names) {
  using Vertex_handle = typename C3t3::Triangulation::Vertex_handle;
  TetMesh mesh;
  mesh.tissue_names = names;
  std::unordered_map<Vertex_handle, int> vindex;  // numbering by first use, as the loop below meets them
  vindex.reserve(c3t3.triangulation().number_of_vertices());
  for (auto cit = c3t3.cells_in_complex_begin(); cit != c3t3.cells_in_complex_end(); ++cit) {
    std::array<int, 4> tet{};
    for (int q = 0; q < 4; ++q) {
      const Vertex_handle v = cit->vertex(q);
      auto [it, fresh] = vindex.emplace(v, static_cast<int>(mesh.points.size()));
      if (fresh) {
        const auto& wp = c3t3.triangulation().point(v);
        mesh.points.push_back(to_physical(wp.x(), wp.y(), wp.z()));
      }
      tet[q] = it->second;
    }
    if (reflect) std::swap(tet[2], tet[3]);
    mesh.tets.push_back(tet);
    mesh.tissue_ids.push_back(static_cast<int>(c3t3.subdomain_index(cit)));
  }
  if (mesh.tets.empty()) throw MeshingError("CGAL Mesh_3 produced no tetrahedra");
  return mesh;
}

}  // namespace tissuemesh::mesh3
