#include "mesher/mesh_report.h"

#include "mesher/conformity.h"
#include "mesher/mesh_quality.h"

#include <cstdio>
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
  j["image_components"] = r.meshing.image_components;
  j["initial_surface_points"] = r.meshing.initial_points;
  j["components_not_meshed"] = missed;
  j["boundary_slivers_removed"] = {{"tets", r.meshing.boundary_slivers.tets_removed},
                                   {"volume_mm3", r.meshing.boundary_slivers.volume_removed_mm3}};
  j["sliver_flips"] = {{"flips_2_3", r.meshing.sliver_flips.flips_23},
                       {"edge_removals", r.meshing.sliver_flips.edge_removals},
                       {"passes", r.meshing.sliver_flips.passes},
                       {"interface_flips", r.meshing.sliver_flips.interface_flips},
                       {"volume_moved_between_tissues_mm3", r.meshing.sliver_flips.volume_relabelled_mm3}};
  return j;
}

std::string mesh_job_text(const MeshJobResult& r) {
  std::ostringstream s;
  const TetMesh& mesh = r.meshing.mesh;
  s << "mesh: " << mesh.points.size() << " nodes, " << mesh.tets.size() << " tets\n\n";
  s << format_quality_table(r.quality) << "\n";
  s << format_conformity_table(r.conformity, mesh.tissue_names) << "\n";
  s << "image components (6-connected, all tissues): " << r.meshing.image_components << "; not meshed: "
    << r.meshing.missed.size() << "\n";
  s << "boundary slivers removed: " << r.meshing.boundary_slivers.tets_removed << " tets, "
    << fmt("%.4f mm^3\n", r.meshing.boundary_slivers.volume_removed_mm3);
  s << "sliver flips: " << r.meshing.sliver_flips.flips_23 << " 2-3 flips, " << r.meshing.sliver_flips.edge_removals
    << " edge removals (" << r.meshing.sliver_flips.interface_flips << " across interfaces, "
    << fmt("%.4f mm^3 moved", r.meshing.sliver_flips.volume_relabelled_mm3) << ") in " << r.meshing.sliver_flips.passes
    << " passes\n";
  for (const auto& w : r.meshing.warnings) s << "WARNING: " << w << "\n";
  for (const auto& m : r.meshing.missed)
    s << "  " << m.tissue << ": " << m.voxels << " voxels, " << fmt("%.2f mm^3 at (%.1f, ", m.volume_mm3, m.centroid_mm[0])
      << fmt("%.1f, %.1f) mm LPS\n", m.centroid_mm[1], m.centroid_mm[2]);
  return s.str();
}

}  // namespace tissuemesh
