#include "pipeline/mesh_report.h"

#include "quality/conformity.h"
#include "quality/mesh_quality.h"

#include <cmath>
#include <cstdio>
#include <map>
#include <optional>
#include <sstream>

namespace tissuemesh {

namespace {

nlohmann::json vec(const Eigen::Vector3d& v) { return {v[0], v[1], v[2]}; }

std::string fmt(const char* format, double a, double b = 0, double c = 0) {
  char buf[160];
  std::snprintf(buf, sizeof buf, format, a, b, c);
  return buf;
}

}  // namespace

nlohmann::json image_summary_json(const LabelImage& image) {
  nlohmann::json j;
  j["dims"] = image.dims;
  j["spacing_mm"] = vec(image.spacing);
  j["origin_mm"] = vec(image.origin);
  j["direction_columns"] = {vec(image.direction.col(0)), vec(image.direction.col(1)), vec(image.direction.col(2))};
  j["orientation"] = orientation_code(image.direction);
  j["coordinate_system"] = "LPS";
  j["voxel_volume_mm3"] = image.voxel_volume();
  nlohmann::json labels = nlohmann::json::array();
  for (const auto& [label, n] : image.label_counts())
    labels.push_back({{"label", label}, {"voxels", n}, {"volume_mm3", n * image.voxel_volume()}});
  j["labels"] = labels;
  return j;
}

std::string image_summary_text(const LabelImage& image) {
  std::ostringstream s;
  s << "label image: " << image.dims[0] << " x " << image.dims[1] << " x " << image.dims[2] << " voxels, spacing "
    << fmt("%.4g x %.4g x %.4g mm", image.spacing[0], image.spacing[1], image.spacing[2]) << "\n";
  s << "  orientation " << orientation_code(image.direction) << " (axes i,j,k point to these patient sides; "
    << "coordinates LPS mm)\n";
  s << "  origin (centre of voxel 0,0,0): " << fmt("(%.3f, %.3f, %.3f) mm", image.origin[0], image.origin[1], image.origin[2])
    << "\n";
  for (int c = 0; c < 3; ++c)
    s << "  axis " << "ijk"[c] << " direction: "
      << fmt("(%.5f, %.5f, %.5f)", image.direction(0, c), image.direction(1, c), image.direction(2, c)) << "\n";
  s << "  label      voxels    volume [mm^3]\n";
  for (const auto& [label, n] : image.label_counts())
    s << fmt("  %5.0f", label) << fmt(" %11.0f", static_cast<double>(n)) << fmt(" %16.1f\n", n * image.voxel_volume());
  return s.str();
}

nlohmann::json mesh_summary_json(const TetMesh& mesh) {
  nlohmann::json j;
  j["nodes"] = mesh.points.size();
  j["tets"] = mesh.tets.size();
  j["tissues"] = mesh.tissue_names;
  j["quality"] = to_json(compute_quality(mesh));
  j["conformity"] = to_json(check_conformity(mesh));
  return j;
}

std::string mesh_summary_text(const TetMesh& mesh) {
  std::ostringstream s;
  s << "tet mesh: " << mesh.points.size() << " nodes, " << mesh.tets.size() << " tets, " << mesh.num_tissues()
    << " tissues (coordinates LPS mm)\n\n";
  s << format_quality_table(compute_quality(mesh)) << "\n";
  s << format_conformity_table(check_conformity(mesh), mesh.tissue_names);
  return s.str();
}

namespace {

void add_sliver_repair_json(nlohmann::json& j, const SliverRepair& repair, const std::vector<std::string>& tissues) {
  const BoundarySliverRemoval& b = repair.boundary_slivers;
  const SliverFlipResult& f = repair.sliver_flips;
  j["boundary_slivers_removed"] = {{"tets", b.tets_removed}, {"volume_mm3", b.volume_removed_mm3}};
  j["sliver_flips"] = {{"flips_2_3", f.flips_23},
                       {"edge_removals", f.edge_removals},
                       {"passes", f.passes},
                       {"interface_flips", f.interface_flips},
                       {"volume_moved_between_tissues_mm3", f.volume_relabelled_mm3}};
  j["sliver_smoothing"] = {{"vertex_moves", repair.sliver_smoothing.moved_vertices},
                           {"vertex_moves_on_curved_surface", repair.sliver_smoothing.moved_on_surface},
                           {"passes", repair.sliver_smoothing.passes}};
  j["sliver_offsets"] = {{"vertex_moves", repair.sliver_offsets.moved_off_surface},
                         {"max_offset_mm", repair.sliver_offsets.max_offset_mm},
                         {"passes", repair.sliver_offsets.passes}};
  j["sliver_splits"] = {{"edges_split", repair.sliver_splits.splits},
                        {"interface_wedges_relabelled", repair.sliver_splits.relabelled_wedges},
                        {"volume_relabelled_mm3", repair.sliver_splits.volume_relabelled_mm3}};
  const BoundaryPinchRepair& p = repair.boundary_pinches;
  nlohmann::json per_tissue = nlohmann::json::object();
  for (std::size_t t = 0; t < p.removed_per_tissue.size(); ++t)
    if (p.removed_per_tissue[t] > 0)
      per_tissue[t < tissues.size() ? tissues[t] : std::to_string(t + 1)] = {{"tets", p.removed_per_tissue[t]}, {"volume_mm3", p.volume_per_tissue_mm3[t]}};
  j["boundary_pinches_opened"] = {{"edges", p.edges_found},        {"edges_left", p.edges_left},
                                  {"tets_removed", p.tets_removed}, {"volume_mm3", p.volume_removed_mm3},
                                  {"passes", p.passes},             {"per_tissue", per_tissue}};
}

std::string sliver_repair_text(const SliverRepair& repair) {
  const BoundarySliverRemoval& b = repair.boundary_slivers;
  const SliverFlipResult& f = repair.sliver_flips;
  std::ostringstream s;
  s << "boundary slivers removed: " << b.tets_removed << " tets, " << fmt("%.4f mm^3\n", b.volume_removed_mm3);
  s << "sliver flips: " << f.flips_23 << " 2-3 flips, " << f.edge_removals << " edge removals (" << f.interface_flips
    << " across interfaces, " << fmt("%.4f mm^3 moved", f.volume_relabelled_mm3) << ") in " << f.passes << " passes\n";
  const SliverSmoothingResult& m = repair.sliver_smoothing;
  s << "sliver smoothing: " << m.moved_vertices
    << " vertex moves (inside a tissue or within a flat or nearly flat boundary or interface";
  if (m.moved_on_surface > 0) s << "; " << m.moved_on_surface << " of them over a curved one, kept on the input's boundaries and interfaces";
  s << ") in " << m.passes << " passes\n";
  if (repair.sliver_splits.splits > 0)
  {
    const SliverSplitResult& sp = repair.sliver_splits;
    s << "sliver splits: " << sp.splits << " edges inside one tissue split (a node added in each)";
    if (sp.relabelled_wedges > 0)
      s << "; " << sp.relabelled_wedges << " of them after giving a flat interface wedge to the tissue around the edge ("
        << fmt("%.4f mm^3 moved", sp.volume_relabelled_mm3) << ")";
    s << "\n";
  }
  const SliverSmoothingResult& o = repair.sliver_offsets;
  if (o.moved_off_surface > 0)
    s << "sliver moves off the surface: " << o.moved_off_surface
      << " moves of boundary or interface vertices of tets still under 10 degrees (sliver_offset_edge_ratio), the surface moved there by at most "
      << fmt("%.3f mm\n", o.max_offset_mm);
  const BoundaryPinchRepair& p = repair.boundary_pinches;
  if (p.edges_found > 0)
    s << "boundary pinches opened: " << p.edges_found << " edges where the outer boundary touched itself, "
      << p.tets_removed << " tets removed, " << fmt("%.4f mm^3", p.volume_removed_mm3) << " in " << p.passes
      << " passes" << (p.edges_left > 0 ? ", " + std::to_string(p.edges_left) + " left" : std::string()) << "\n";
  return s.str();
}

std::string tissue_name(int id, const std::vector<std::string>& names) {
  if (id == 0) return "outside";
  return id > 0 && static_cast<std::size_t>(id) <= names.size() ? names[id - 1] : "tissue " + std::to_string(id);
}

// Both pipelines report absorbed islands alike: per tissue, the components that went, their voxels
// and volume, and which tissue (or outside) took the voxels.
nlohmann::json islands_json(const IslandAbsorption& a, const std::vector<std::string>& names) {
  nlohmann::json tissues = nlohmann::json::array();
  for (const TissueIslands& t : a.tissues) {
    nlohmann::json into = nlohmann::json::array();
    for (const auto& [id, n] : t.voxels_into)
      into.push_back({{"tissue", tissue_name(id, names)}, {"voxels", n},
                      {"volume_mm3", t.voxels > 0 ? t.volume_mm3 * static_cast<double>(n) / static_cast<double>(t.voxels) : 0.0}});
    tissues.push_back({{"tissue", tissue_name(t.tissue_id, names)}, {"components", t.islands}, {"voxels", t.voxels},
                       {"volume_mm3", t.volume_mm3}, {"into", into}});
  }
  nlohmann::json kept = nlohmann::json::array();
  for (const auto& [id, n] : a.kept_whole) kept.push_back({{"tissue", tissue_name(id, names)}, {"voxels", n}});
  return {{"below_voxels", a.min_voxels}, {"components", a.islands}, {"voxels", a.voxels},
          {"volume_mm3", a.volume_mm3}, {"complete", a.complete}, {"tissues", tissues},
          {"kept_whole", kept}};
}

std::string islands_text(const IslandAbsorption& a, const std::vector<std::string>& names) {
  std::ostringstream s;
  s << "components under " << a.min_voxels << " voxels given to their surroundings: " << a.islands << " ("
    << a.voxels << " voxels, " << fmt("%.2f mm^3)\n", a.volume_mm3);
  if (!a.complete) s << "  (pass limit reached: some nested islands are left)\n";
  for (const TissueIslands& t : a.tissues) {
    char name[64];
    std::snprintf(name, sizeof name, "  %-16s", tissue_name(t.tissue_id, names).c_str());
    s << name << fmt(" %8.0f components %10.0f voxels", static_cast<double>(t.islands), static_cast<double>(t.voxels))
      << fmt(" %12.2f mm^3  ->", t.volume_mm3);
    for (const auto& [id, n] : t.voxels_into) s << " " << tissue_name(id, names) << " " << n;
    s << " voxels\n";
  }
  for (const auto& [id, n] : a.kept_whole)
    s << "  " << tissue_name(id, names) << ": its largest component (" << n << " voxels) is under the threshold and kept"
      << " (a tissue is never removed whole)\n";
  return s.str();
}

void add_missed_text(std::ostringstream& s, const std::vector<MissedComponent>& missed) {
  for (const auto& m : missed)
    s << "  " << m.tissue << ": " << m.voxels << " voxels, " << fmt("%.2f mm^3 at (%.1f, ", m.volume_mm3, m.centroid_mm[0])
      << fmt("%.1f, %.1f) mm LPS\n", m.centroid_mm[1], m.centroid_mm[2]);
}

nlohmann::json deviations_json(const std::vector<VolumeDeviation>& deviations) {
  nlohmann::json out = nlohmann::json::array();
  for (const VolumeDeviation& d : deviations)
    out.push_back({{"tissue", d.tissue}, {"volume_mm3", d.volume_mm3},
                   {"reference_volume_mm3", d.reference_volume_mm3}, {"error_percent", d.error_percent}});
  return out;
}

nlohmann::json sizing_json(const DirectSizing& z, std::size_t tets) {
  if (z.target_tets == 0) return nullptr;
  nlohmann::json attempts = nlohmann::json::array();
  for (const auto& a : z.attempts)
    attempts.push_back({{"largest_edge_mm", a.global_edge_mm}, {"predicted_tets", a.predicted_tets},
                        {"refined_tets", a.refined_tets}});
  nlohmann::json coarsened = nlohmann::json::array();
  for (const auto& c : z.coarsened) coarsened.push_back({{"tissue", c.tissue}, {"thin_volume_mm3", c.thin_volume_mm3}});
  return {{"target_tets", z.target_tets},
          {"tets", tets},
          {"off_target_percent", 100.0 * (static_cast<double>(tets) / static_cast<double>(z.target_tets) - 1.0)},
          {"smallest_edge_mm", z.min_edge_mm},
          {"largest_edge_mm", z.global_edge_mm},
          {"tet_volume_factor", z.tet_volume_factor},
          {"thin_parts_coarsened_by", z.thickness_scale},
          {"tissues_thinner_than_their_elements", coarsened},
          {"refinements", attempts}};
}

std::string sizing_text(const DirectSizing& z, std::size_t tets) {
  if (z.target_tets == 0) return "";
  std::ostringstream s;
  s << "sizes from the image: " << tets << " tets for a budget of " << z.target_tets
    << fmt(" (%+.1f %%); edges ", 100.0 * (static_cast<double>(tets) / static_cast<double>(z.target_tets) - 1.0))
    << fmt("%.2f to ", z.min_edge_mm) << fmt("%.2f mm, ", z.global_edge_mm) << z.attempts.size() << " refinement(s)\n";
  if (z.thickness_scale > 1.0)
    s << fmt("  at this budget thin parts get elements %.2f times their local thickness x thickness_edge_ratio:\n",
             z.thickness_scale);
  for (const auto& c : z.coarsened)
    s << "  " << c.tissue << fmt(": %.1f mm^3 thinner than its elements\n", c.thin_volume_mm3);
  return s.str();
}

}  // namespace

nlohmann::json mesh_job_json(const MeshJobResult& r) {
  nlohmann::json j;
  const TetMesh& mesh = r.meshing.mesh;
  j["nodes"] = mesh.points.size();
  j["tets"] = mesh.tets.size();
  j["tissues"] = mesh.tissue_names;
  j["quality"] = to_json(r.quality);
  j["conformity"] = to_json(r.conformity);
  j["conforming"] = r.conformity.conforming();
  nlohmann::json missed = nlohmann::json::array();
  for (const auto& m : r.meshing.missed)
    missed.push_back({{"tissue", m.tissue}, {"voxels", m.voxels}, {"volume_mm3", m.volume_mm3},
                      {"centroid_mm", vec(m.centroid_mm)}});
  j["warnings"] = r.meshing.warnings;
  j["volume_outside_tolerance"] = deviations_json(r.volume_deviations);
  j["image_components"] = r.meshing.image_components;
  j["components_absorbed"] = islands_json(r.meshing.absorbed, mesh.tissue_names);
  j["components_meshed"] = r.meshing.meshed_components;
  j["initial_surface_points"] = r.meshing.initial_points;
  j["components_not_meshed"] = missed;
  std::map<std::string, std::pair<std::size_t, double>> missed_by_tissue;  // components, volume
  for (const auto& m : r.meshing.missed) {
    auto& [n, volume] = missed_by_tissue[m.tissue];
    ++n;
    volume += m.volume_mm3;
  }
  nlohmann::json by_tissue = nlohmann::json::array();
  for (const auto& [tissue, nv] : missed_by_tissue)
    by_tissue.push_back({{"tissue", tissue}, {"components", nv.first}, {"volume_mm3", nv.second}});
  j["components_not_meshed_by_tissue"] = by_tissue;
  add_sliver_repair_json(j, r.meshing.repair, r.meshing.mesh.tissue_names);
  j["sizes_from_image"] = sizing_json(r.meshing.sizing, mesh.tets.size());
  const ComponentVolumeFit& f = r.meshing.island_fit;
  j["island_volume_fit"] = {{"fitted", f.fitted}, {"not_enclosed", f.not_enclosed}, {"blocked", f.blocked},
                            {"volume_moved_mm3", f.volume_moved_mm3}};
  return j;
}

std::string mesh_job_text(const MeshJobResult& r) {
  std::ostringstream s;
  const TetMesh& mesh = r.meshing.mesh;
  s << "mesh: " << mesh.points.size() << " nodes, " << mesh.tets.size() << " tets\n\n";
  s << format_quality_table(r.quality) << "\n";
  s << format_conformity_table(r.conformity, mesh.tissue_names) << "\n";
  s << "image components (6-connected, all tissues): " << r.meshing.image_components << "\n";
  if (r.meshing.absorbed.min_voxels > 1) s << islands_text(r.meshing.absorbed, mesh.tissue_names);
  s << sizing_text(r.meshing.sizing, mesh.tets.size());
  s << "components meshed: " << r.meshing.meshed_components << " from " << r.meshing.initial_points
    << " initial surface points; not meshed: " << r.meshing.missed.size() << "\n";
  add_missed_text(s, r.meshing.missed);
  s << sliver_repair_text(r.meshing.repair);
  const ComponentVolumeFit& f = r.meshing.island_fit;
  if (f.fitted + f.blocked + f.not_enclosed > 0)
    s << "small components scaled to their voxel volume: " << f.fitted << fmt(" (%.2f mm^3 moved); ", f.volume_moved_mm3)
      << f.blocked << " left as meshed (a tet would have gone below its angle), " << f.not_enclosed
      << " not enclosed by one tissue\n";
  for (const auto& w : r.meshing.warnings) s << "WARNING: " << w << "\n";
  return s.str();
}

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

// Table 2 of Alqaoud et al. (see mesh_report.h): vertices and cells of each tissue after each step
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

// Each tissue's tet volume against its voxel volume before the tet volume restoration, percent,
// in tissue order.
std::vector<std::pair<std::string, double>> errors_before_restoration(const TetVolumeRestoration& t,
                                                                      const std::map<int, double>& voxel_mm3,
                                                                      const std::vector<std::string>& names) {
  std::vector<std::pair<std::string, double>> out;
  for (const auto& [id, v] : t.offsets.volume_before_mm3) {
    const auto ref = voxel_mm3.find(id);
    if (ref == voxel_mm3.end() || id < 1 || id > static_cast<int>(names.size()) || ref->second <= 0.0) continue;
    out.emplace_back(names[id - 1], 100.0 * (v / ref->second - 1.0));
  }
  return out;
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
                                           {"stopped_to_stay_intersection_free", r.restoration->stopped_early}};
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
        vj["volume_restoration"] = {{"rounds", t->offsets.rounds},
                                    {"nodes_moved", t->nodes_moved},
                                    {"max_offset_mm", t->max_offset_mm},
                                    {"nodes_held", t->offsets.frozen_vertices},
                                    {"stopped_early", t->offsets.stopped_early},
                                    {"volume_error_percent_before",
                                     errors_before_restoration(*t, r.voxel_volume_mm3, v.meshing.mesh.tissue_names)}};
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
        << "\n";
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
  o << table1_row(r.remesh ? "remeshed" : "extracted", r.quality) << "\n";
  o << "surface checks      vertices  triangles  closed+oriented+manifold  intersecting pairs  volume [mm^3]  voxel volume [mm^3]  error [%]\n";
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
        o << "tet volume restoration: " << t->offsets.rounds << " rounds of patch offsets moved " << t->nodes_moved
          << " boundary and interface nodes, largest move " << fmt("%.3f", t->max_offset_mm) << " mm";
        if (t->offsets.frozen_vertices > 0)
          o << "; " << t->offsets.frozen_vertices << " nodes held where a round would have flattened a tet";
        o << "; before it";
        for (const auto& [name, percent] : errors_before_restoration(*t, r.voxel_volume_mm3, v.meshing.mesh.tissue_names))
          o << " " << name << fmt(" %+.2f %%", percent);
        o << "\n";
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
