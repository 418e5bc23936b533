#include "pipeline/surface_job.h"

#include "pipeline/mesh_job.h"

#include "core/number_format.h"
#include "surface/thickness_size.h"
#include "surface/triangle_geometry.h"

#include <algorithm>
#include <cmath>
#include <future>
#include <limits>
#include <optional>


namespace tissuemesh {

namespace {

void mesh_volume(SurfaceJobResult& r, const MeshConfig& config, const ThicknessSize* thickness, Progress& progress) {
  if (!r.checks.valid()) return;
  if (r.quality.min_angle_deg < kMinAngleForVolumeDeg) {
    // Such slivers of triangles make CGAL's protecting balls at the junctions ever smaller: the
    // volume stage would run for hours, if it ended at all.
    r.volume_refused = "the surface has a triangle with an angle of " + format_double("%.3f", r.quality.min_angle_deg) +
                       " deg (under " + format_double("%g", kMinAngleForVolumeDeg) +
                       " deg), too thin for the volume mesher's junction protection to finish in reasonable time; raise "
                       "surface.target_vertices or give more small islands to their surroundings "
                       "(surface.min_island_voxels)";
    return;
  }
  VolumeStage v;
  v.size_mm = r.remesh ? r.remesh->edge_length_mm : r.quality.mean_edge_mm;  // r.quality: of r.surface()
  const ApproachField* field = r.approach ? &*r.approach : nullptr;
  const double L = v.size_mm;
  // The tets keep the thin parts' bound too (scaled as the remesher scaled it for the budget).
  const double scale = r.remesh ? r.remesh->thickness_scale : 1.0;
  if (scale == 0.0) thickness = nullptr;  // dropped by the remesher
  const std::function<double(const Eigen::Vector3d&)> h = [L, field, thickness, scale](const Eigen::Vector3d& p) {
    const double size = field ? L * field->relative_size(p) : L;
    return thickness ? std::min(size, scale * (*thickness)(p)) : size;
  };
  v.mesher = config.volume.mesher;
  if (v.mesher == "tetgen") {
    SurfaceTetgenResult t = mesh_surface_with_tetgen(r.surface(), h, config.volume, config.tetgen, progress);
    v.meshing.mesh = std::move(t.mesh);
    v.meshing.repair = t.repair;
    v.meshing.warnings = std::move(t.warnings);
    v.tetgen_switches = t.switches;
    v.steiner_points = t.steiner_points;
    v.cell_edge_factor = t.cell_edge_factor;
    v.budget = std::move(t.budget);
  } else {
    // CGAL resamples the surface: a restored surface would lose volume again in the chords of the
    // tets' boundary, so the tets are restored too.
    static const std::map<int, double> kNone;
    v.meshing = mesh_complex(r.surface(), h, config.volume, progress,
                             config.surface.restore_volumes ? r.voxel_volume_mm3 : kNone);
  }
  auto stage = progress.stage("volume mesh quality and conformity");
  v.quality = compute_quality(v.meshing.mesh, r.voxel_volume_mm3);
  v.conformity = check_conformity(v.meshing.mesh);
  v.volume_deviations = volume_deviations(v.quality, config.checks);
  for (std::string& w : volume_warnings(v.volume_deviations, config.checks)) v.meshing.warnings.push_back(std::move(w));
  r.volume = std::move(v);
}

}  // namespace

SurfaceJobResult run_surface_job(const LabelImage& labels, const std::string& image_name, const MeshConfig& config,
                                 Progress& progress) {
  SurfaceJobResult r;
  const LabelImage ids = tissue_id_image(labels, image_name, config.tissues, r.voxel_volume_mm3, progress);
  r.extraction = extract_surface(ids, config.tissues.names(), config.surface, progress);
  r.extracted_quality = surface_quality(r.extraction.surface);
  r.checks = r.extraction.checks;
  r.quality = r.extracted_quality;
  if (!config.surface.remesh() || !r.extraction.checks.valid()) {
    r.sharpest_fold_deg = sharpest_fold_deg(r.extraction.surface);
    mesh_volume(r, config, nullptr, progress);
    return r;
  }
  // A stage of its own, so that every second between extraction and remeshed surface is timed
  // (bench/bench_surface.sh counts it with the remeshing).
  const SurfaceProjection on_extracted = [&] {
    auto stage = progress.stage("projection onto the extracted surface");
    return SurfaceProjection(r.extraction.surface);
  }();
  RemeshOptions options;
  options.target_vertices = config.surface.target_vertices;
  options.target_edge_mm = config.surface.target_edge_mm;
  options.iterations = config.surface.remesh_iterations;
  options.mean_quality_passes = config.surface.mean_quality_passes;
  options.max_deviation_mm = 0.5 * ids.spacing.norm();  // half a voxel diagonal
  if (config.approach.enabled) {
    r.approach.emplace(r.extraction.surface, config.approach);
    const ApproachField* field = &*r.approach;
    options.relative_size = [field](const Eigen::Vector3d& p) { return field->relative_size(p); };
  }
  std::optional<ThicknessSize> thickness;
  // Thin parts: edges bounded by the local thickness (of the tissue ids as configured; the few
  // voxels absorbed as islands only make the bound finer next to where they were).
  if (config.surface.thickness_edge_ratio > 0.0) {
    auto stage = progress.stage("local thickness of the tissues");
    // Only thicknesses whose bound may come under the edge length matter: up to twice the uniform
    // edge of the budget (or the target edge) over the ratio (the cost of the thickness map grows
    // with that cap). The smallest bound is a voxel.
    double area = 0.0;
    const TriSurface& e = r.extraction.surface;
    for (const auto& t : e.triangles) area += area_vector(e.points[t[0]], e.points[t[1]], e.points[t[2]]).norm();
    const double uniform = options.target_vertices > 0
                               ? std::sqrt(2.0 * area / (std::sqrt(3.0) * options.target_vertices))
                               : options.target_edge_mm;
    const double cap_mm = 2.0 * uniform / config.surface.thickness_edge_ratio;
    thickness.emplace(ids, cap_mm, config.surface.thickness_edge_ratio, ids.spacing.minCoeff());
    stage.note(std::to_string(thickness->thin_voxels()) + " voxels under " + format_double("%.2f", cap_mm) +
               " mm thick");
    r.thickness_edge_ratio = config.surface.thickness_edge_ratio;
    const ThicknessSize* t = &*thickness;
    options.max_edge_mm = [t](const Eigen::Vector3d& p) { return (*t)(p); };
  }
  // Remeshing of r's extracted surface, volume restoration, surface quality, then the volume stage
  // with the Hausdorff distance beside it, into `out` (r itself, or a second try).
  auto remesh_and_mesh = [&](SurfaceJobResult& out) {
    out.remesh = remesh_surface(r.extraction.surface, on_extracted, options, progress);
    if (config.surface.restore_volumes && out.remesh->checks.valid()) {
      auto stage = progress.stage("volume restoration");
      out.restoration = restore_volumes(out.remesh->surface, out.voxel_volume_mm3);
      out.remesh->checks = check_surface(out.remesh->surface);
      stage.note(std::to_string(out.restoration->rounds) + " offset rounds, largest move " +
                 format_double("%.3f", out.restoration->max_offset_mm) + " mm");
    }
    {
      auto stage = progress.stage("remeshed surface quality");
      out.checks = out.remesh->checks;
      out.quality = surface_quality(out.remesh->surface);
      out.sharpest_fold_deg = sharpest_fold_deg(out.remesh->surface);
      if (out.approach) out.grading = measure_grading(out.remesh->surface, *out.approach);
    }
    // The Hausdorff distance only measures: it runs on one thread of its own beside the volume
    // stage (one thread but for short parts), which reads the surface as it does and changes
    // nothing of it, and is waited for after it (or, on an exception, by the future's destructor).
    std::future<SurfaceDistance> hausdorff = std::async(std::launch::async, [&out, &r, &on_extracted] {
      const SurfaceProjection on_remeshed(out.remesh->surface);
      return hausdorff_distance(out.remesh->surface, on_remeshed, r.extraction.surface, on_extracted, 1);
    });
    mesh_volume(out, config, thickness ? &*thickness : nullptr, progress);
    auto stage = progress.stage("Hausdorff distance to the extracted surface (beside the volume mesh)");
    out.hausdorff = hausdorff.get();
  };
  remesh_and_mesh(r);
  // TetGen keeps every surface triangle, so a fold of the surface (a fin thinner than the edges,
  // coarsened and smoothed flat) becomes tets as flat as it; the sliver repair's last resort
  // lifts most. Where tets under 10 degrees remain, the remeshing runs again with the fold guard
  // (RemeshOptions::fold_guard) and that mesh is kept if it has fewer of them (or, as many, a
  // larger smallest angle). Not always: the guard changes the remeshing's path, which can cost a
  // surface that needed no guard some of Table 1's smallest angle.
  const auto under_10 = [](const SurfaceJobResult& x) {
    return x.volume ? x.volume->quality.total.tets_below_10deg : std::numeric_limits<std::size_t>::max();
  };
  if (config.volume.mesher == "tetgen" && r.volume && under_10(r) > 0) {
    FoldRerun rerun;
    rerun.sharpest_before_deg = r.sharpest_fold_deg;
    rerun.tets_under_10_before = under_10(r);
    SurfaceJobResult guarded;
    {
      auto stage = progress.stage("again with the fold guard (" + std::to_string(under_10(r)) +
                                  " tets under 10 deg, sharpest surface fold " +
                                  format_double("%.2f", r.sharpest_fold_deg) + " deg)");
      // What remesh_and_mesh reads besides r's extraction.
      guarded.voxel_volume_mm3 = r.voxel_volume_mm3;
      guarded.approach = r.approach;
      options.fold_guard = true;
      remesh_and_mesh(guarded);
      rerun.sharpest_after_deg = guarded.sharpest_fold_deg;
      rerun.tets_under_10_after = under_10(guarded);
      const bool conforming = guarded.volume && guarded.volume->conformity.conforming();
      rerun.kept = conforming && (under_10(guarded) < under_10(r) ||
                                  (under_10(guarded) == under_10(r) && guarded.volume->quality.total.min_dihedral_deg >
                                                                          r.volume->quality.total.min_dihedral_deg));
      stage.note(std::to_string(under_10(guarded)) + " tets under 10 deg, sharpest fold " +
                 format_double("%.2f", guarded.sharpest_fold_deg) + " deg: " + (rerun.kept ? "kept" : "discarded"));
    }
    if (rerun.kept) {
      r.remesh = std::move(guarded.remesh);
      r.restoration = std::move(guarded.restoration);
      r.checks = std::move(guarded.checks);
      r.quality = guarded.quality;
      r.sharpest_fold_deg = guarded.sharpest_fold_deg;
      r.grading = std::move(guarded.grading);
      r.hausdorff = std::move(guarded.hausdorff);
      r.volume = std::move(guarded.volume);
      r.volume_refused = std::move(guarded.volume_refused);
    }
    r.fold_rerun = rerun;
  }
  return r;
}

}  // namespace tissuemesh
