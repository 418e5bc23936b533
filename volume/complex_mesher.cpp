// The one CGAL-heavy translation unit of the surface pipeline's volume mesher.
//
// Why: CGAL's polyhedral complex domain takes 2-manifold polyhedra, hence the split of every patch
// into manifold pieces. Protecting balls on the piece borders (junction curves) keep them sharp
// and conforming between all patches around them. CGAL's random initialisation misses small
// parts, so pieces without borders (a tumour inside the gland) get initial points of their own and
// no closed component is skipped. The domain answers its region queries from a free-cell grid
// (volume/free_cell_domain.h) with CGAL's own answers, only faster.
#include "volume/complex_mesher.h"

#include "core/errors.h"
#include "core/number_format.h"
#include "volume/budget_refinement.h"
#include "volume/free_cell_domain.h"
#include "volume/mesh3_steps.h"
#include "volume/surface_pieces.h"
#include "surface/surface_projection.h"
#include "surface/surface_quality.h"
#include "volume/tet_volume_restoration.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Mesh_complex_3_in_triangulation_3.h>
#include <CGAL/Mesh_criteria_3.h>
#include <CGAL/Mesh_triangulation_3.h>
#include <CGAL/Mesh_polyhedron_3.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polyhedral_complex_mesh_domain_3.h>
#include <CGAL/make_mesh_3.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <memory>
#include <optional>
#include <sstream>
#include <utility>

namespace tissuemesh {

namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Polyhedron = CGAL::Mesh_polyhedron_3<K>::type;
using Domain = FreeCellDomain;
using Tr = CGAL::Mesh_triangulation_3<Domain, CGAL::Default, CGAL::Sequential_tag>::type;
using C3t3 = CGAL::Mesh_complex_3_in_triangulation_3<Tr, Domain::Corner_index, Domain::Curve_index>;
using Criteria = CGAL::Mesh_criteria_3<Tr>;
using Point = K::Point_3;

// Bounds of the size factor solved under volume.target_tets.
constexpr double kFinestFactor = 0.25;
constexpr double kCoarsestFactor = 16.0;

// A CGAL sizing field: factor * h(x), mm, whatever the dimension and index.
struct Sizing {
  typedef K::FT FT;
  typedef K::Point_3 Point_3;
  typedef Domain::Index Index;
  const std::function<double(const Eigen::Vector3d&)>* h = nullptr;
  double factor = 1.0;
  FT operator()(const Point_3& p, const int, const Index&) const {
    return factor * (*h)(Eigen::Vector3d(p.x(), p.y(), p.z()));
  }
};

Polyhedron to_polyhedron(const SurfacePiece& piece) {
  std::vector<Point> points;
  points.reserve(piece.points.size());
  for (const auto& p : piece.points) points.emplace_back(p[0], p[1], p[2]);
  std::vector<std::vector<std::size_t>> polygons;
  polygons.reserve(piece.triangles.size());
  for (const auto& t : piece.triangles) polygons.push_back({std::size_t(t[0]), std::size_t(t[1]), std::size_t(t[2])});
  if (!CGAL::Polygon_mesh_processing::is_polygon_soup_a_polygon_mesh(polygons))
    throw MeshingError("a patch piece " + std::to_string(piece.pair[0]) + "|" + std::to_string(piece.pair[1]) +
                       " is not a manifold surface (a bug in the piece split)");
  Polyhedron poly;
  CGAL::Polygon_mesh_processing::polygon_soup_to_polygon_mesh(points, polygons, poly);
  return poly;
}


// Throws the InputError of a missed volume.target_tets, naming the counts and factors reached.
void check_budget(std::size_t target, const std::vector<BudgetRound>& rounds, const std::vector<SizeRound>& sizes) {
  if (!budget_missed(target, rounds)) return;
  std::ostringstream e;
  e << "volume.target_tets: a budget of " << target << " tets cannot be met on this surface; CGAL gave";
  std::size_t fewest = rounds.front().count, most = 0;
  for (const BudgetRound& b : rounds) {
    e << " " << b.count;
    fewest = std::min(fewest, b.count);
    most = std::max(most, b.count);
  }
  e << " tets (size factors";
  for (const SizeRound& b : sizes) e << " " << format_double("%.3g", b.factor);
  e << ")";
  if (rounds.back().count < target)
    e << ": lower volume.target_tets to at most " << most;
  else
    e << ": the count no longer follows the sizes (thin layers and junctions hold it up); raise "
         "volume.target_tets to at least "
      << fewest + fewest / 10 << ", or lower surface.target_vertices";
  throw InputError(e.str());
}

}  // namespace

ComplexMeshResult mesh_complex(const TriSurface& surface, const std::function<double(const Eigen::Vector3d&)>& size_mm,
                               const VolumeMeshParams& params, Progress& progress,
                               const std::map<int, double>& restore_to_mm3) {
  surface.validate("the surface to mesh");
  ComplexMeshResult result;
  std::vector<Polyhedron> polyhedra;
  std::vector<std::pair<int, int>> sides;
  {
    auto stage = progress.stage("patch pieces");
    const SurfacePieces split = manifold_pieces(surface);
    result.pieces = split.pieces.size();
    result.duplicated_vertices = split.duplicated_vertices;
    for (const SurfacePiece& piece : split.pieces) {
      polyhedra.push_back(to_polyhedron(piece));
      sides.emplace_back(piece.pair[0], piece.pair[1]);
    }
    stage.note(std::to_string(result.pieces) + " pieces, " + std::to_string(result.duplicated_vertices) +
               " vertices duplicated");
  }
  if (polyhedra.empty()) throw InputError("the surface to mesh has no triangles");

  auto domain_stage = std::make_unique<Progress::Stage>(progress, "domain and junction features");
  Domain domain(polyhedra.begin(), polyhedra.end(), sides.begin(), sides.end());
  // Piece borders (junction curves) and creases sharper than feature_angle_deg become features.
  domain.detect_features(params.feature_angle_deg);
  const double mean_edge_mm = surface_quality(surface).mean_edge_mm;
  const auto [grid, unknown] = domain.index_regions(surface, 0.5 * mean_edge_mm);
  domain_stage->note(std::to_string(grid->components()) + " free-cell regions (" + std::to_string(unknown) +
                     " left to rays), " + std::to_string(static_cast<int>(100 * grid->free_share())) +
                     " % of the grid free");
  domain_stage.reset();

  // Interior grading: the tet edge grows with the distance from the nearest surface triangle.
  std::optional<SurfaceProjection> projection;
  std::function<double(const Eigen::Vector3d&)> cell_size_mm = size_mm;
  if (params.cell_growth > 0.0 || params.max_cell_edge_mm > 0.0) {
    projection.emplace(surface);
    const SurfaceProjection* near = &*projection;
    const double growth = params.cell_growth, cap = params.max_cell_edge_mm;
    cell_size_mm = [&size_mm, near, growth, cap](const Eigen::Vector3d& x) {
      const double e = size_mm(x) + (growth > 0.0 ? growth * near->distance(x) : 0.0);
      return cap > 0.0 ? std::min(e, cap) : e;
    };
  }
  const double distance_mm = params.facet_distance_mm > 0 ? params.facet_distance_mm : 0.1 * mean_edge_mm;

  // The smoothing may move vertices of curved interfaces over the input surface (they stay on it);
  // the projection's trees are built only when it runs.
  SurfaceProjector onto_surface;
  if (params.optimise.smooth_slivers_below_deg > 0) {
    if (!projection) projection.emplace(surface);
    onto_surface = [&](int p, int q, Eigen::Vector3d& x) {
      const int patch = projection->patches().patch_of_pair(p, q);
      if (patch < 0) return false;
      x = projection->onto_patch(patch, x);
      return true;
    };
  }

  // One CGAL refinement and optimisation with every size (facet, junction edge, cell, facet
  // distance) times `factor`; the tets counted are those before the sliver repair, which changes
  // the count by a few.
  std::unique_ptr<C3t3> c3t3;
  auto refine_with = [&](double factor) {
    namespace p = CGAL::parameters;
    // The equilateral triangle of edge e has circumradius e / sqrt(3); the regular tet of edge e
    // has circumradius e sqrt(6) / 4.
    const Sizing edge{&size_mm, factor * params.surface_edge_factor};
    const Sizing facet{&size_mm, factor * params.surface_edge_factor / std::sqrt(3.0)};
    const Sizing cell{&cell_size_mm, factor * params.cell_edge_factor * std::sqrt(6.0) / 4.0};
    // Under a budget a facet must have its three vertices on one patch (or its borders): the
    // facet distance grows with the factor, and in a layer thinner than the facets (the skin) a
    // facet from one side to the other would pass it (skin -25 % on the phantom at a factor of
    // 6); this rule refines such a facet whatever the distance. Without a budget the default
    // distance catches them, and the rule would only add tets (15 % at 2.1K).
    const CGAL::Mesh_facet_topology topology =
        params.target_tets > 0 ? CGAL::FACET_VERTICES_ON_SAME_SURFACE_PATCH : CGAL::FACET_VERTICES_ON_SURFACE;
    Criteria criteria(p::edge_size = edge, p::facet_angle = params.facet_angle_deg, p::facet_size = facet,
                      p::facet_distance = factor * distance_mm, p::cell_radius_edge_ratio = params.cell_radius_edge_ratio,
                      p::cell_size = cell, p::facet_topology = topology);
    c3t3 = std::make_unique<C3t3>();
    {
      auto stage = progress.stage("protect junctions, seed pieces");
      CGAL::Mesh_3::internal::init_c3t3_with_features(*c3t3, domain, criteria);
      domain.add_patch_seeds(*c3t3);
      result.initial_points = c3t3->triangulation().number_of_vertices();
      stage.note(std::to_string(result.initial_points) + " initial points" +
                 (params.target_tets > 0 ? ", size factor " + format_double("%.3g", factor) : std::string()));
    }
    mesh3::refine(*c3t3, domain, criteria, progress);
    result.warnings.clear();
    mesh3::optimise(*c3t3, domain, params.optimise, progress, result.warnings);
    result.size_factor = factor;
    return static_cast<std::size_t>(c3t3->number_of_cells_in_complex());
  };

  if (params.target_tets == 0) {
    refine_with(1.0);
  } else {
    // The count of a surface-bound mesh falls about as 1 / factor here (the facets of the surface
    // go as factor^-2, but thin layers and junctions hold part of the count up), so the rounds
    // solve in the measure R = 1 / factor, from a first factor guessed at about four tets per
    // surface triangle at factor 1.
    const double guess = 4.0 * static_cast<double>(surface.triangles.size()) / static_cast<double>(params.target_tets);
    const double start = std::clamp(guess, kFinestFactor, kCoarsestFactor);
    const std::vector<BudgetRound> rounds = meet_count_budget(params.target_tets, [&](double R) {
      const double factor = std::clamp(R > 0.0 ? 1.0 / R : start, kFinestFactor, kCoarsestFactor);
      return BudgetRound{1.0 / factor, refine_with(factor), factor <= kFinestFactor};
    });
    for (const BudgetRound& b : rounds) result.budget.push_back({1.0 / b.measure, b.count});
    check_budget(params.target_tets, rounds, result.budget);
  }

  {
    auto stage = progress.stage("extract mesh");
    result.mesh = mesh3::cells(
        *c3t3, [](double x, double y, double z) { return Eigen::Vector3d(x, y, z); }, false, surface.tissue_names);
    c3t3.reset();
    stage.note(std::to_string(result.mesh.tets.size()) + " tets, " + std::to_string(result.mesh.points.size()) +
               " nodes");
  }
  {
    auto stage = progress.stage("sliver repair");
    result.repair = repair_slivers(result.mesh, params.optimise, result.warnings, onto_surface);
    stage.note(std::to_string(result.mesh.tets.size()) + " tets");
  }
  // After the repairs: their flips across interfaces and projections onto the input surface
  // would undo part of it, and it lowers no tet under 10 degrees (tet_volume_restoration.h).
  if (!restore_to_mm3.empty()) {
    auto stage = progress.stage("tet volume restoration");
    result.restoration = restore_tet_volumes(result.mesh, restore_to_mm3);
    stage.note(std::to_string(result.restoration->offsets.rounds) + " rounds, " +
               std::to_string(result.restoration->nodes_moved) + " nodes moved");
  }
  return result;
}

}  // namespace tissuemesh
