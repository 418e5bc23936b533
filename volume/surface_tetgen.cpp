// Why the repairs are restricted: the point of this stage is that the tet mesh's boundary and
// interfaces are the remeshed surface, with its volumes and its Table 1 quality; a repair that
// moved them would trade that for a few degrees of dihedral angle. The one exception is the last
// resort (sliver_offset_edge_ratio), for the few tets that would otherwise stay under 10 degrees:
// a tenth of an edge at a handful of vertices costs no measurable volume.
#include "volume/surface_tetgen.h"

#include "core/errors.h"
#include "core/number_format.h"
#include "volume/tetgen_mesher.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace tissuemesh {

namespace {

// A budget moves cell_edge_factor within [kFinestFactor, kCoarsestFactor], starting from the
// configured factor (kStartFactor when it is 0). Coarser bounds than kCoarsestFactor hold TetGen's
// quality refinement back near the surface (its size bound also spaces the points it adds), so
// that the count no longer falls but the angles do; the mesh without a bound is the coarsest.
constexpr double kFinestFactor = 0.1;
constexpr double kCoarsestFactor = 3.0;
constexpr double kStartFactor = 1.5;
constexpr double kTolerance = 0.10;  // as budget_missed

}  // namespace

SurfaceTetgenResult mesh_surface_with_tetgen(const TriSurface& surface,
                                             const std::function<double(const Eigen::Vector3d&)>& size_mm,
                                             const VolumeMeshParams& params, const TetgenParams& tetgen,
                                             Progress& progress) {
  surface.validate("the surface to mesh");
  if (surface.triangles.empty()) throw InputError("the surface to mesh has no triangles");
  // h at every surface point once; the circumradius of the regular tet of edge e is e sqrt(6) / 4.
  std::vector<double> h(surface.points.size());
  for (std::size_t v = 0; v < h.size(); ++v) {
    h[v] = size_mm(surface.points[v]);
    if (!(h[v] > 0.0 && std::isfinite(h[v])))
      throw InputError("volume mesh: the size field is not a positive finite number at surface point " +
                       std::to_string(v));
  }
  TetgenParams q = tetgen;
  q.max_volume_mm3.clear();  // sizes come from h alone
  SurfaceTetgenResult result;
  TetgenResult kept;
  // factor 0: no size bound (TetGen reads a circumradius bound of 0 as none at that point).
  auto mesh_with = [&](double factor) {
    std::vector<double> radius(h.size());
    for (std::size_t v = 0; v < h.size(); ++v) radius[v] = factor * h[v] * std::sqrt(6.0) / 4.0;
    kept = tetgen_mesh(surface, q, progress, radius);
    result.cell_edge_factor = factor;
    return kept.mesh.tets.size();
  };

  if (params.target_tets == 0) {
    mesh_with(params.cell_edge_factor);
  } else {
    const double target = static_cast<double>(params.target_tets);
    // The mesh without a size bound has the fewest tets TetGen gives for this surface.
    const std::size_t fewest = mesh_with(0.0);
    result.budget.push_back({0.0, fewest, false});
    const double off = static_cast<double>(fewest) / target - 1.0;
    if (off > kTolerance)
      throw InputError("volume.target_tets: a budget of " + std::to_string(params.target_tets) +
                       " tets cannot be met on this surface: without a size bound TetGen gives " +
                       std::to_string(fewest) + " tets, the fewest that keep every surface triangle at the "
                       "quality bound; raise volume.target_tets to at least " + std::to_string(fewest + fewest / 10) +
                       ", or lower surface.target_vertices");
    if (off < -kTolerance) {
      // Measure R = factor^-3: the count of a size-bounded mesh grows about as 1 / edge^3.
      const double start = params.cell_edge_factor > 0.0 ? params.cell_edge_factor : kStartFactor;
      const std::vector<BudgetRound> rounds = meet_count_budget(params.target_tets, [&](double R) {
        const double factor = std::clamp(R > 0.0 ? std::pow(R, -1.0 / 3.0) : start, kFinestFactor, kCoarsestFactor);
        const std::size_t tets = mesh_with(factor);
        return BudgetRound{std::pow(factor, -3.0), tets, factor <= kFinestFactor};
      });
      result.budget.insert(result.budget.end(), rounds.begin(), rounds.end());
      if (budget_missed(params.target_tets, rounds)) {
        std::ostringstream e;
        e << "volume.target_tets: a budget of " << params.target_tets << " tets cannot be met on this surface; TetGen gave";
        std::size_t most = 0;
        for (const BudgetRound& r : result.budget) {
          e << " " << r.count;
          most = std::max(most, r.count);
        }
        e << " tets";
        if (rounds.back().count < params.target_tets)
          e << " (cell_edge_factor down to " << kFinestFactor << "): lower volume.target_tets to at most " << most;
        else
          e << ": between the mesh without a size bound (" << fewest << " tets) and cell_edge_factor " << kCoarsestFactor
            << " the count does not follow the sizes; set volume.cell_edge_factor instead";
        throw InputError(e.str());
      }
    }
  }
  result.mesh = std::move(kept.mesh);
  if (kept.unseeded.tets > 0) result.warnings.push_back(unseeded_warning(kept.unseeded));
  result.switches = kept.switches;
  result.steiner_points = kept.steiner_points;

  auto stage = progress.stage("sliver repair inside the tissues");
  Mesh3Optimisation keep_surface = params.optimise;
  keep_surface.remove_boundary_slivers_deg = 0.0;
  keep_surface.interface_flips = false;
  // The splits may still give a flat wedge under 10 degrees to the tissue around one of its
  // edges (when the config allows interface flips): the surface then moves by that wedge, of
  // near-zero volume, where TetGen had to fill a crease of it with a flat tet of four surface
  // nodes that nothing else that keeps the surface can remove.
  keep_surface.split_relabels = params.optimise.interface_flips;
  keep_surface.smooth_near_planar_deg = 0.0;
  result.repair = repair_slivers(result.mesh, keep_surface, result.warnings);
  stage.note(std::to_string(result.mesh.tets.size()) + " tets, " + std::to_string(result.mesh.points.size()) +
             " nodes");
  return result;
}

}  // namespace tissuemesh
