#include "pipeline/mesh_report.h"

#include "pipeline/report_parts.h"

#include "quality/conformity.h"
#include "quality/mesh_quality.h"

#include <cmath>
#include <cstdio>
#include <map>
#include <optional>
#include <sstream>

namespace tissuemesh {

using namespace report_parts;  // the shared parts (pipeline/report_parts.h)

namespace {

nlohmann::json vec(const Eigen::Vector3d& v) { return {v[0], v[1], v[2]}; }


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

void add_missed_text(std::ostringstream& s, const std::vector<MissedComponent>& missed) {
  for (const auto& m : missed)
    s << "  " << m.tissue << ": " << m.voxels << " voxels, " << fmt("%.2f mm^3 at (%.1f, ", m.volume_mm3, m.centroid_mm[0])
      << fmt("%.1f, %.1f) mm LPS\n", m.centroid_mm[1], m.centroid_mm[2]);
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
  if (const auto& t = r.meshing.restoration)
    j["volume_restoration"] = tet_restoration_json(*t, r.voxel_volume_mm3, mesh.tissue_names);
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
  if (const auto& t = r.meshing.restoration) s << tet_restoration_text(*t, r.voxel_volume_mm3, mesh.tissue_names);
  for (const auto& w : r.meshing.warnings) s << "WARNING: " << w << "\n";
  return s.str();
}

}  // namespace tissuemesh
