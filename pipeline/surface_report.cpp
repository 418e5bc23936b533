#include "pipeline/surface_report.h"

#include "pipeline/report_parts.h"
#include "quality/conformity.h"
#include "quality/mesh_quality.h"
#include "volume/direct_mesher.h"

#include <cmath>
#include <cstdio>
#include <map>
#include <optional>
#include <sstream>

namespace tissuemesh {

using namespace report_parts;  // the shared parts (pipeline/report_parts.h)

namespace {
double voxel_volume_of(const TissueSurfaceCheck& t, const std::map<int, double>& voxel_volume_mm3) {
  const auto it = voxel_volume_mm3.find(t.tissue_id);
  return it == voxel_volume_mm3.end() ? 0.0 : it->second;
}

double volume_error_percent(const TissueSurfaceCheck& t, const std::map<int, double>& voxel_volume_mm3) {
  const double voxel = voxel_volume_of(t, voxel_volume_mm3);
  return voxel > 0.0 ? 100.0 * (t.volume_mm3 - voxel) / voxel : 0.0;
}
}  // namespace

namespace {

nlohmann::json table1_json(const SurfaceQuality& q) {
  return {{"average_min_angle_deg", q.average_min_angle_deg}, {"min_angle_deg", q.min_angle_deg},
          {"p30_percent", q.p30_percent},  {"q_average", q.q_average},
          {"q_min", q.q_min},                 {"mean_edge_mm", q.mean_edge_mm}};
}

std::string table1_row(const char* name, const SurfaceQuality& q) {
  char label[40];
  std::snprintf(label, sizeof label, "  %-26s", name);
  return label + fmt("  %19.3f  %15.3f", q.average_min_angle_deg, q.min_angle_deg) +
         fmt("  %7.4f  %6.4f  %6.4f", q.p30_percent, q.q_average, q.q_min) + fmt("  %14.3f\n", q.mean_edge_mm);
}

// Table 2 of Alqaoud et al. (see surface_report.h): vertices and cells of each tissue after each step
// (1 extracted surface, 2 remeshed surface, 3 tet mesh), plus a row for the whole complex. A surface
// vertex on an interface counts in both tissues, as in the paper; the whole-complex row counts it
// once.
struct StepCounts {
  std::size_t vertices = 0, cells = 0;
};
struct StepsRow {
  std::string tissue;
  StepCounts extracted;
  std::optional<StepCounts> remeshed, volume;
};

std::vector<StepsRow> steps_table(const SurfaceJobResult& r) {
  std::vector<StepsRow> rows;
  const auto& extracted = r.extraction.checks.tissues;
  for (std::size_t t = 0; t < extracted.size(); ++t) {
    StepsRow row;
    row.tissue = extracted[t].name;
    row.extracted = {extracted[t].vertices, extracted[t].triangles};
    if (r.remesh) row.remeshed = StepCounts{r.remesh->checks.tissues[t].vertices, r.remesh->checks.tissues[t].triangles};
    if (r.volume) row.volume = StepCounts{r.volume->quality.tissues[t].vertices, r.volume->quality.tissues[t].tets};
    rows.push_back(row);
  }
  StepsRow all;
  all.tissue = "all tissues";
  all.extracted = {r.extraction.surface.points.size(), r.extraction.surface.triangles.size()};
  if (r.remesh) all.remeshed = StepCounts{r.remesh->surface.points.size(), r.remesh->surface.triangles.size()};
  if (r.volume) all.volume = StepCounts{r.volume->meshing.mesh.points.size(), r.volume->meshing.mesh.tets.size()};
  rows.push_back(all);
  return rows;
}

nlohmann::json table2_json(const std::vector<StepsRow>& rows) {
  auto counts = [](const std::optional<StepCounts>& c, const char* cells) {
    return c ? nlohmann::json{{"vertices", c->vertices}, {cells, c->cells}} : nlohmann::json(nullptr);
  };
  nlohmann::json j = nlohmann::json::array();
  for (const auto& row : rows)
    j.push_back({{"tissue", row.tissue},
                 {"extracted_surface", counts(row.extracted, "triangles")},
                 {"remeshed_surface", counts(row.remeshed, "triangles")},
                 {"tet_mesh", counts(row.volume, "tets")}});
  return j;
}

std::string table2_text(const std::vector<StepsRow>& rows) {
  std::ostringstream o;
  o << "Table 2 (vertices and cells after each step)\n"
    << "                    1 extracted surface    2 remeshed surface         3 tet mesh\n"
    << "  tissue             vertices  triangles    vertices  triangles    vertices       tets\n";
  auto pair = [](const std::optional<StepCounts>& c) {
    char cell[64];
    if (c)
      std::snprintf(cell, sizeof cell, "  %10zu %10zu", c->vertices, c->cells);
    else
      std::snprintf(cell, sizeof cell, "  %10s %10s", "-", "-");
    return std::string(cell);
  };
  for (const auto& row : rows) {
    char name[64];
    std::snprintf(name, sizeof name, "  %-16s", row.tissue.c_str());
    o << name << pair(row.extracted) << pair(row.remeshed) << pair(row.volume) << "\n";
  }
  o << "  (a vertex on an interface counts in each tissue it bounds; the last row counts it once)\n";
  return o.str();
}

}  // namespace

nlohmann::json surface_job_json(const SurfaceJobResult& r) {
  const TriSurface& s = r.surface();
  const TriSurface& e = r.extraction.surface;
  nlohmann::json j;
  j["vertices"] = s.points.size();
  j["triangles"] = s.triangles.size();
  j["junction_polylines"] = s.junctions.size();
  j["extracted"] = {{"vertices", e.points.size()},
                    {"triangles", e.triangles.size()},
                    {"junction_curve_vertices", r.extraction.curve_vertices},
                    {"junction_corner_vertices", r.extraction.corner_vertices},
                    {"unfolded_vertex_moves", r.extraction.unfolded_vertices},
                    {"islands_absorbed", islands_json(r.extraction.islands, e.tissue_names)},
                    {"voxel_repair",
                     {{"relabelled_voxels", r.extraction.repair.relabelled_voxels},
                      {"passes", r.extraction.repair.passes}}},
                    {"table1_quality", table1_json(r.extracted_quality)}};
  if (r.remesh) {
    j["remesh"] = {{"edge_length_mm", r.remesh->edge_length_mm},
                   {"splits", r.remesh->splits},
                   {"collapses", r.remesh->collapses},
                   {"flips", r.remesh->flips},
                   {"angle_smoothing_moves", r.remesh->angle_moves},
                   {"quality_smoothing_moves", r.remesh->quality_moves},
                   {"mean_quality_smoothing_moves", r.remesh->mean_quality_moves},
                   {"sweeps_on_two_threads", r.remesh->partitioned_sweeps},
                   {"thickness_edge_ratio", r.thickness_edge_ratio},
                   {"thickness_scale", r.remesh->thickness_scale}};
    if (r.hausdorff)
      j["remesh"]["hausdorff_to_extracted_mm"] = {{"symmetric", r.hausdorff->symmetric_mm()},
                                                   {"remeshed_to_extracted", r.hausdorff->a_to_b_mm},
                                                   {"extracted_to_remeshed", r.hausdorff->b_to_a_mm}};
    if (r.restoration)
      j["remesh"]["volume_restoration"] = {{"offset_rounds", r.restoration->rounds},
                                           {"largest_move_mm", r.restoration->max_offset_mm},
                                           {"vertices_held", r.restoration->frozen_vertices},
                                           {"stopped_to_stay_intersection_free", r.restoration->stopped_early},
                                           {"tissues_released", released_names(*r.restoration, s.tissue_names)}};
    if (r.fold_rerun)
      j["remesh"]["fold_guard_rerun"] = {{"sharpest_fold_before_deg", r.fold_rerun->sharpest_before_deg},
                                         {"sharpest_fold_guarded_deg", r.fold_rerun->sharpest_after_deg},
                                         {"tets_under_10deg_before", r.fold_rerun->tets_under_10_before},
                                         {"tets_under_10deg_guarded", r.fold_rerun->tets_under_10_after},
                                         {"kept", r.fold_rerun->kept}};
  }
  if (r.approach) {
    const Eigen::Vector3d &e = r.approach->entry(), &c = r.approach->target_centroid();
    j["approach"] = {{"entry_mm", {e.x(), e.y(), e.z()}},
                     {"target_centroid_mm", {c.x(), c.y(), c.z()}},
                     {"target_radius_mm", r.approach->target_radius_mm()},
                     {"corridor_radius_mm", r.approach->params().corridor_radius_mm}};
    if (r.grading)
      j["approach"]["measured"] = {{"inside_mean_edge_mm", r.grading->inside_mean_edge_mm},
                                   {"outside_mean_edge_mm", r.grading->outside_mean_edge_mm},
                                   {"inside_edges", r.grading->inside_edges},
                                   {"outside_edges", r.grading->outside_edges},
                                   {"inside_over_outside", r.grading->ratio()}};
  }
  j["table1_quality"] = table1_json(r.quality);
  j["sharpest_fold_deg"] = r.sharpest_fold_deg;
  nlohmann::json tissues = nlohmann::json::array();
  for (const auto& t : r.checks.tissues)
    tissues.push_back({{"tissue", t.name},
                       {"vertices", t.vertices},
                       {"triangles", t.triangles},
                       {"closed_and_oriented", t.closed_and_oriented()},
                       {"open_edges", t.open_edges},
                       {"nonmanifold_edges", t.nonmanifold_edges},
                       {"misoriented_edges", t.misoriented_edges},
                       {"nonmanifold_vertices", t.nonmanifold_vertices},
                       {"intersecting_triangle_pairs", t.intersecting_pairs},
                       {"enclosed_volume_mm3", t.volume_mm3},
                       {"voxel_volume_mm3", voxel_volume_of(t, r.voxel_volume_mm3)},
                       {"volume_error_percent", volume_error_percent(t, r.voxel_volume_mm3)}});
  j["table2_tissues"] = tissues;
  j["duplicate_triangles"] = r.checks.duplicate_triangles;
  j["junction_edges"] = r.checks.junction_edges;
  j["junction_edges_off_junction"] = r.checks.junction_edges_off_junction;
  j["valid"] = r.checks.valid();
  if (r.volume) {
    const VolumeStage& v = *r.volume;
    nlohmann::json vj;
    vj["size_field_edge_mm"] = v.size_mm;
    vj["nodes"] = v.meshing.mesh.points.size();
    vj["tets"] = v.meshing.mesh.tets.size();
    if (v.mesher == "tetgen") {
      vj["mesher"] = "TetGen 1.5 from the surface, every surface triangle kept";
      vj["tetgen_switches"] = v.tetgen_switches;
      vj["steiner_points"] = v.steiner_points;
      vj["cell_edge_factor"] = v.cell_edge_factor;
      nlohmann::json rounds = nlohmann::json::array();
      for (const BudgetRound& b : v.budget)
        rounds.push_back({{"cell_edge_factor", b.measure > 0.0 ? std::pow(b.measure, -1.0 / 3.0) : 0.0}, {"tets", b.count}});
      vj["target_tets_rounds"] = rounds;
    } else {
      vj["mesher"] = "CGAL Mesh_3 " + cgal_version() + " from the surface (Polyhedral_complex_mesh_domain_3)";
      vj["patch_pieces"] = v.meshing.pieces;
      vj["duplicated_piece_vertices"] = v.meshing.duplicated_vertices;
      vj["initial_points"] = v.meshing.initial_points;
      vj["size_factor"] = v.meshing.size_factor;
      nlohmann::json rounds = nlohmann::json::array();
      for (const SizeRound& b : v.meshing.budget) rounds.push_back({{"size_factor", b.factor}, {"tets", b.tets}});
      vj["target_tets_rounds"] = rounds;
      if (const auto& t = v.meshing.restoration) {
        vj["volume_restoration"] = tet_restoration_json(*t, r.voxel_volume_mm3, v.meshing.mesh.tissue_names);
      }
    }
    vj["quality"] = to_json(v.quality);
    vj["conformity"] = to_json(v.conformity);
    vj["conforming"] = v.conformity.conforming();
    add_sliver_repair_json(vj, v.meshing.repair, v.meshing.mesh.tissue_names);
    vj["warnings"] = v.meshing.warnings;
    vj["volume_outside_tolerance"] = deviations_json(v.volume_deviations);
    j["volume_mesh"] = vj;
  }
  j["table2_steps"] = table2_json(steps_table(r));
  if (r.volume) j["table3_total_cells"] = r.volume->meshing.mesh.tets.size();
  if (!r.volume_refused.empty()) j["volume_mesh_refused"] = r.volume_refused;
  return j;
}

std::string surface_job_text(const SurfaceJobResult& r) {
  const TriSurface& e = r.extraction.surface;
  const TriSurface& s = r.surface();
  std::ostringstream o;
  o << "extracted surface: " << e.points.size() << " vertices, " << e.triangles.size()
    << " triangles (each interface once), " << e.junctions.size() << " junction polylines ("
    << r.extraction.curve_vertices << " curve vertices, " << r.extraction.corner_vertices << " corners); "
    << r.extraction.islands.islands << " islands (" << r.extraction.islands.voxels
    << " voxels) given to their surroundings, " << r.extraction.repair.relabelled_voxels
    << " voxels relabelled to remove non-manifold configurations, "
    << r.extraction.unfolded_vertices << " vertex moves to undo folds\n";
  if (r.extraction.islands.min_voxels > 1) o << islands_text(r.extraction.islands, e.tissue_names);
  if (r.remesh) {
    o << "remeshed surface: " << s.points.size() << " vertices, " << s.triangles.size() << " triangles, "
      << s.junctions.size() << " junction polylines; edge length " << fmt("%.3f", r.remesh->edge_length_mm)
      << " mm where the size field is 1 (" << r.remesh->splits << " splits, " << r.remesh->collapses
      << " collapses, " << r.remesh->flips << " flips, " << r.remesh->angle_moves << " angle-smoothing moves";
    if (r.remesh->quality_moves > 0) o << ", " << r.remesh->quality_moves << " quality-smoothing moves";
    if (r.remesh->mean_quality_moves > 0) o << ", " << r.remesh->mean_quality_moves << " mean-quality moves";
    o << "; " << r.remesh->partitioned_sweeps << " collapse and relaxation sweeps in two halves on two threads)\n";
    if (r.thickness_edge_ratio > 0.0) {
      if (r.remesh->thickness_scale == 0.0)
        o << "thin parts: not bounded by their thickness (at " << fmt("%g", r.thickness_edge_ratio)
          << " x the local thickness they would take far more than half the vertex budget; uniform sizes instead)";
      else
        o << "thin parts: edges at most " << fmt("%g", r.thickness_edge_ratio) << " x the local thickness";
      if (r.remesh->thickness_scale > 1.0)
        o << " x " << fmt("%.2f", r.remesh->thickness_scale)
          << " (coarsened: at the ratio alone they would take more than half the vertex budget)";
      o << "\n";
    }
    if (r.restoration)
      o << "volume restoration: " << r.restoration->rounds << " rounds of patch offsets, largest move "
        << fmt("%.3f", r.restoration->max_offset_mm) << " mm"
        << (r.restoration->frozen_vertices > 0
                ? "; " + std::to_string(r.restoration->frozen_vertices) +
                      " vertices held in place where a round would have broken the surface"
                : std::string())
        << (r.restoration->stopped_early ? " (stopped where a further round would make the surface invalid)" : "")
        << released_text(*r.restoration, s.tissue_names) << "\n";
    if (r.hausdorff)
      o << "Hausdorff distance to the extracted surface: " << fmt("%.3f", r.hausdorff->symmetric_mm())
        << " mm (remeshed -> extracted " << fmt("%.3f", r.hausdorff->a_to_b_mm) << " mm, extracted -> remeshed "
        << fmt("%.3f", r.hausdorff->b_to_a_mm) << " mm)\n";
  }
  if (r.approach && r.grading) {
    const Eigen::Vector3d &e = r.approach->entry();
    o << "approach: entry " << fmt("(%.2f, %.2f, %.2f) mm", e.x(), e.y(), e.z()) << ", mean edge "
      << fmt("%.3f mm inside the corridor and target (%.0f edges), ", r.grading->inside_mean_edge_mm,
             static_cast<double>(r.grading->inside_edges))
      << fmt("%.3f mm beyond the falloff (%.0f edges): ratio %.3f\n", r.grading->outside_mean_edge_mm,
             static_cast<double>(r.grading->outside_edges), r.grading->ratio());
  }
  o << "\nTable 1 (triangle quality)    avg min angle [deg]  min angle [deg]  P30 [%]   Q_av    Q_min   mean edge [mm]\n";
  if (r.remesh) o << table1_row("extracted", r.extracted_quality);
  o << table1_row(r.remesh ? "remeshed" : "extracted", r.quality);
  o << "sharpest fold (two triangles of one patch across an edge; 180 = flat): " << fmt("%.2f", r.sharpest_fold_deg)
    << " deg\n";
  if (r.fold_rerun)
    o << "remeshed and meshed again with the fold guard: the first mesh had "
      << r.fold_rerun->tets_under_10_before << " tets under 10 deg (sharpest surface fold "
      << fmt("%.2f", r.fold_rerun->sharpest_before_deg) << " deg), the guarded one "
      << r.fold_rerun->tets_under_10_after << " (" << fmt("%.2f", r.fold_rerun->sharpest_after_deg) << " deg): "
      << (r.fold_rerun->kept ? "kept" : "discarded") << "\n";
  o << "\nsurface checks      vertices  triangles  closed+oriented+manifold  intersecting pairs  volume [mm^3]  voxel volume [mm^3]  error [%]\n";
  for (const auto& t : r.checks.tissues) {
    char line[256];
    std::snprintf(line, sizeof line, "  %-16s  %8zu  %9zu  %24s  %18lld  %13.1f  %19.1f  %9.3f\n", t.name.c_str(),
                  t.vertices, t.triangles, t.closed_and_oriented() && t.nonmanifold_vertices == 0 ? "yes" : "NO",
                  t.intersecting_pairs, t.volume_mm3,
                  voxel_volume_of(t, r.voxel_volume_mm3), volume_error_percent(t, r.voxel_volume_mm3));
    o << line;
  }
  o << "\ntriangles stored twice: " << r.checks.duplicate_triangles << "; junction edges: " << r.checks.junction_edges
    << " (" << r.checks.junction_edges_off_junction << " not where >= 3 triangles meet)\n";
  o << (r.checks.valid() ? "surface valid: every tissue closed, oriented and intersection free\n"
                         : "WARNING: the surface fails a check above; no volume mesh\n");
  o << "\n" << table2_text(steps_table(r));
  if (r.volume) o << "Table 3 (total cells): " << r.volume->meshing.mesh.tets.size() << " tets\n";
  if (r.volume) {
    const VolumeStage& v = *r.volume;
    if (v.mesher == "tetgen") {
      o << "\nvolume mesh (TetGen -" << v.tetgen_switches << " from the surface, every surface triangle kept; size "
        << "field edge " << fmt("%.3f mm", v.size_mm) << ", cell_edge_factor " << fmt("%.3g", v.cell_edge_factor)
        << "): " << v.meshing.mesh.points.size() << " nodes (" << v.steiner_points << " added by TetGen), "
        << v.meshing.mesh.tets.size() << " tets\n";
      if (!v.budget.empty()) {
        o << "volume.target_tets: TetGen gave";
        for (const BudgetRound& b : v.budget) o << " " << b.count;
        o << " tets (cell_edge_factor";
        for (const BudgetRound& b : v.budget) o << " " << fmt("%.3g", b.measure > 0.0 ? std::pow(b.measure, -1.0 / 3.0) : 0.0);
        o << "; 0 = no size bound)\n";
      }
      o << "\n";
    } else {
      o << "\nvolume mesh (CGAL Mesh_3 from the surface, size field edge " << fmt("%.3f mm", v.size_mm);
      if (v.meshing.size_factor != 1.0) o << " x size factor " << fmt("%.3g", v.meshing.size_factor);
      o << "): " << v.meshing.mesh.points.size() << " nodes, " << v.meshing.mesh.tets.size() << " tets, "
        << v.meshing.pieces << " patch pieces\n";
      if (!v.meshing.budget.empty()) {
        o << "volume.target_tets: CGAL gave";
        for (const SizeRound& b : v.meshing.budget) o << " " << b.tets;
        o << " tets (size factor";
        for (const SizeRound& b : v.meshing.budget) o << " " << fmt("%.3g", b.factor);
        o << ")\n";
      }
      if (const auto& t = v.meshing.restoration) {
        o << tet_restoration_text(*t, r.voxel_volume_mm3, v.meshing.mesh.tissue_names);
      }
      o << "\n";
    }
    o << format_quality_table(v.quality) << "\n";
    o << format_conformity_table(v.conformity, v.meshing.mesh.tissue_names) << "\n";
    o << sliver_repair_text(v.meshing.repair);
    for (const auto& w : v.meshing.warnings) o << "WARNING: " << w << "\n";
  }
  if (!r.volume_refused.empty()) o << "\nno volume mesh: " << r.volume_refused << "\n";
  return o.str();
}

}  // namespace tissuemesh
