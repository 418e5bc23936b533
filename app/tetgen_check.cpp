#include "app/tetgen_check.h"

#include "app/check_outputs.h"
#include "app/cli_support.h"
#include "app/export_outputs.h"
#include "core/errors.h"
#include "core/vtu_io.h"
#include "quality/conformity.h"
#include "volume/forced_radius_edge.h"
#include "quality/mesh_interfaces.h"
#include "quality/mesh_quality.h"
#include "quality/node_spacing.h"
#include "volume/tetgen_mesher.h"
#include "solver_check/tissue_motion.h"

#include <Eigen/Geometry>

#include <cmath>
#include <cstdio>
#include <iostream>
#include <map>
#include <sstream>

namespace tissuemesh::app {

namespace {

/// Area of every interface (p, q), mm^2.
std::map<std::pair<int, int>, double> interface_areas(const TriSurface& s) {
  std::map<std::pair<int, int>, double> areas;
  for (std::size_t t = 0; t < s.triangles.size(); ++t) {
    const auto& k = s.triangles[t];
    areas[{s.labels[t][0], s.labels[t][1]}] +=
        0.5 * (s.points[k[1]] - s.points[k[0]]).cross(s.points[k[2]] - s.points[k[0]]).norm();
  }
  return areas;
}

std::string region_name(const TetMesh& mesh, int id) { return id == 0 ? "outside" : mesh.tissue_names[id - 1]; }

double percent(double value, double reference) { return reference != 0.0 ? 100.0 * (value - reference) / reference : 0.0; }

struct SolvedMesh {
  SolveResult solve;
  TissueMotion target;
};

SolvedMesh solve_mesh(const TetMesh& mesh, const std::string& target, const JobConfig& config, Progress& progress) {
  const Model model = build_job_model(mesh, config, progress);
  SolvedMesh r;
  r.solve = solve_builtin(model, progress);
  for (const TissueMotion& m : tissue_motion(model, r.solve.displacements).tissues)
    if (m.name == target) r.target = m;
  return r;
}

// One mesh's figures for one tissue in check.json.
nlohmann::json side_json(const TissueQuality& q) {
  return {{"tets", q.tets},
          {"nodes", q.vertices},
          {"volume_mm3", q.volume_mm3},
          {"min_dihedral_deg", q.min_dihedral_deg},
          {"max_dihedral_deg", q.max_dihedral_deg},
          {"tets_below_10deg", q.tets_below_10deg},
          {"mean_radius_ratio", q.mean_radius_ratio},
          {"max_radius_edge_ratio", q.max_radius_edge_ratio},
          {"tets_radius_edge_above_2", q.tets_radius_edge_above_2}};
}

// "p|q" of regions p and q (tissue names, "outside").
std::string interface_name(const TetMesh& mesh, int p, int q) { return region_name(mesh, p) + "|" + region_name(mesh, q); }

// The triangle that sets the forced ratio: its interface and centroid (mm).
std::string interface_name(const TriSurface& s, const TetMesh& mesh, int t) {
  return interface_name(mesh, s.labels[t][0], s.labels[t][1]);
}

Eigen::Vector3d centroid(const TriSurface& s, int t) {
  const auto& k = s.triangles[t];
  return (s.points[k[0]] + s.points[k[1]] + s.points[k[2]]) / 3.0;
}

nlohmann::json forced_json(const ForcedRadiusEdge& f, const TriSurface& s, const TetMesh& mesh) {
  nlohmann::json j = {{"ratio", f.ratio}, {"input_triangles_above_bound", f.triangles_above_bound}};
  if (f.triangle < 0) return j;
  nlohmann::json corners = nlohmann::json::array();
  for (int v : s.triangles[f.triangle]) corners.push_back(vec_json(s.points[v]));
  j["triangle"] = {{"index", f.triangle},
                   {"interface", interface_name(s, mesh, f.triangle)},
                   {"min_angle_deg", f.min_angle_deg},
                   {"centroid_mm", vec_json(centroid(s, f.triangle))},
                   {"vertices_mm", corners}};
  return j;
}

// How a mesh's tets above the radius-edge bound split into forced and unforced ones.
nlohmann::json account_json(const RadiusEdgeAccount& a) {
  return {{"above", a.above},
          {"forced_by_input_triangle", a.forced},
          {"not_forced", a.unforced},
          {"max_ratio_not_forced", a.max_unforced_ratio},
          {"not_forced_by_surface_nodes", a.unforced_by_surface_nodes}};
}

// "a/b/c/d/e": the unforced tets with 0, 1, ... 4 nodes on the surface.
std::string surface_nodes_text(const RadiusEdgeAccount& a) {
  std::string text;
  for (std::size_t k = 0; k < a.unforced_by_surface_nodes.size(); ++k)
    text += (k ? "/" : "") + std::to_string(a.unforced_by_surface_nodes[k]);
  return text;
}

// The stdout lines of the forced ratio (volume/forced_radius_edge.h).
std::string forced_text(const ForcedRadiusEdge& f, const TriSurface& s, const TetMesh& mesh, const std::string& bound) {
  if (f.triangle < 0) return "";
  const Eigen::Vector3d c = centroid(s, f.triangle);
  std::ostringstream text;
  text << "  forced by the input (each input triangle stays a tet face: TetGen -Y, MESH): ratio >= 1 / (2 sin(smallest "
          "triangle angle)), largest "
       << format_double("%.3f", f.ratio) << " (" << interface_name(s, mesh, f.triangle) << " triangle " << f.triangle
       << ", " << format_double("%.2f", f.min_angle_deg) << " deg, centroid (" << format_double("%.2f", c.x()) << ", "
       << format_double("%.2f", c.y()) << ", " << format_double("%.2f", c.z()) << ") mm)\n"
       << "  input triangles forcing more than " << bound << ": " << f.triangles_above_bound << " of "
       << s.triangles.size()
       << (f.triangles_above_bound > 0 ? " (no mesh keeping them meets the bound)\n" : "\n");
  return text.str();
}

}  // namespace

TetgenCheck tetgen_check_into(const TetMesh& mesh, const std::string& target, const JobConfig& config,
                              const nlohmann::json& inputs, const std::string& cmd, Progress& progress, OutputDir& out) {
  bool known = false;
  for (const auto& name : mesh.tissue_names) known = known || name == target;
  if (!known) throw InputError("--target: '" + target + "' is not a tissue of the mesh");

  TriSurface surface;
  std::vector<double> sizes;  // TetGen's largest circumradius per surface point (mm), empty = none
  {
    auto stage = progress.stage("interfaces of the mesh");
    std::vector<int> node_of_point;
    surface = interface_surface(mesh, &node_of_point);
    if (config.mesh.tetgen.size_from_mesh) {
      const std::vector<double> radius = largest_incident_circumradius_mm(mesh);
      for (int node : node_of_point) sizes.push_back(radius[node]);
    }
    stage.note(std::to_string(surface.triangles.size()) + " triangles");
  }
  const TetgenResult tg = tetgen_mesh(surface, config.mesh.tetgen, progress, sizes);
  const std::string sizing = sizes.empty() ? "per-tissue volume bounds"
                                           : "sizes from MESH: at each surface node its largest tet circumradius";
  {
    auto stage = progress.stage("write mesh_tetgen.vtu");
    write_vtu(tg.mesh, out.stage("mesh_tetgen.vtu").string());
  }
  QualityReport q_mesh, q_tg;
  ConformityReport c_mesh, c_tg;
  std::map<std::pair<int, int>, double> a_mesh, a_tg;
  const double bound = config.mesh.tetgen.radius_edge_ratio;
  RadiusEdgeAccount above_mesh, above_tg;
  ForcedRadiusEdge forced;
  {
    auto stage = progress.stage("compare the meshes");
    q_mesh = compute_quality(mesh);
    q_tg = compute_quality(tg.mesh);
    above_mesh = account_radius_edge_above(mesh, surface, bound);
    above_tg = account_radius_edge_above(tg.mesh, surface, bound);
    forced = forced_radius_edge_ratio(surface, bound);
    c_mesh = check_conformity(mesh);
    c_tg = check_conformity(tg.mesh);
    a_mesh = interface_areas(surface);
    a_tg = interface_areas(interface_surface(tg.mesh));
  }
  const SolvedMesh s_mesh = solve_mesh(mesh, target, config, progress);
  const SolvedMesh s_tg = solve_mesh(tg.mesh, target, config, progress);

  TetgenCheck check;
  check.both_converged = s_mesh.solve.converged && s_tg.solve.converged;
  nlohmann::json tissues = nlohmann::json::array();
  std::ostringstream text;
  char line[256];
  text << "\nTetGen cross-check (TetGen " << tg.switches << " on the " << surface.triangles.size()
       << " boundary and interface triangles of MESH; " << sizing << "):\n";
  std::snprintf(line, sizeof line, "  %-10s %10s %10s %14s %14s %8s %9s %9s\n", "tissue", "tets", "tets TG",
                "volume [mm^3]", "TG [mm^3]", "diff [%]", "min [deg]", "TG [deg]");
  text << line;
  auto row = [&](const TissueQuality& a, const TissueQuality& b) {
    const double diff = percent(b.volume_mm3, a.volume_mm3);
    if (a.id != 0) check.max_volume_difference_percent = std::max(check.max_volume_difference_percent, std::abs(diff));
    std::snprintf(line, sizeof line, "  %-10s %10zu %10zu %14.2f %14.2f %8.4f %9.2f %9.2f\n", a.name.c_str(), a.tets,
                  b.tets, a.volume_mm3, b.volume_mm3, diff, a.min_dihedral_deg, b.min_dihedral_deg);
    text << line;
    tissues.push_back({{"tissue", a.name},
                       {"mesh", side_json(a)},
                       {"tetgen", side_json(b)},
                       {"volume_difference_percent", diff}});
  };
  for (std::size_t i = 0; i < q_mesh.tissues.size(); ++i) row(q_mesh.tissues[i], q_tg.tissues[i]);
  row(q_mesh.total, q_tg.total);
  const std::string bound_text = format_double("%g", bound);
  text << "  radius-edge ratio (circumradius / shortest edge, TetGen's -q measure; tetgen.radius_edge_ratio "
       << bound_text << "): max " << format_double("%.3f", q_mesh.total.max_radius_edge_ratio) << " MESH, "
       << format_double("%.3f", q_tg.total.max_radius_edge_ratio) << " TetGen; tets above " << bound_text << ": "
       << above_mesh.above << " MESH, " << above_tg.above << " TetGen\n"
       << "  of them on an input triangle forcing more than " << bound_text << " (see below): " << above_mesh.forced
       << " MESH, " << above_tg.forced << " TetGen; the others (not forced by the input): " << above_mesh.unforced
       << " MESH (max " << format_double("%.3f", above_mesh.max_unforced_ratio) << "), " << above_tg.unforced
       << " TetGen (max " << format_double("%.3f", above_tg.max_unforced_ratio) << "); of TetGen's, with 0-4 nodes on "
       << "the input surface: " << surface_nodes_text(above_tg) << "\n";
  text << forced_text(forced, surface, mesh, bound_text);

  nlohmann::json interfaces = nlohmann::json::array();
  text << "\n  interface            area [mm^2]     TG [mm^2]   diff [%]\n";
  for (const auto& [pair, area] : a_mesh) {
    const double other = a_tg.count(pair) ? a_tg.at(pair) : 0.0;
    const std::string name = interface_name(mesh, pair.first, pair.second);
    std::snprintf(line, sizeof line, "  %-18s %13.2f %13.2f %10.6f\n", name.c_str(), area, other, percent(other, area));
    text << line;
    interfaces.push_back({{"interface", name}, {"mesh_area_mm2", area}, {"tetgen_area_mm2", other},
                          {"difference_percent", percent(other, area)}});
  }

  const Eigen::Vector3d d_mesh = s_mesh.target.mean_displacement_mm, d_tg = s_tg.target.mean_displacement_mm;
  check.target_displacement_difference_percent = d_mesh.norm() > 0 ? 100.0 * (d_tg - d_mesh).norm() / d_mesh.norm() : 0.0;
  text << "\n  " << target << " volume-mean displacement under gravity (built-in solver): MESH "
       << format_double("%.4f", d_mesh.norm()) << " mm, TetGen " << format_double("%.4f", d_tg.norm()) << " mm, |difference| "
       << format_double("%.3f", check.target_displacement_difference_percent) << " % of MESH's\n";
  text << "  conforming: MESH " << (c_mesh.conforming() ? "yes" : "NO") << ", TetGen "
       << (c_tg.conforming() ? "yes" : "NO") << "; largest tissue volume difference "
       << format_double("%.4f", check.max_volume_difference_percent) << " %\n";
  const std::string unseeded = unseeded_warning(tg.unseeded);
  if (!unseeded.empty()) text << "WARNING: TetGen's mesh: " << unseeded << "\n";
  if (!check.both_converged)
    text << "WARNING: a built-in solve did not converge (MESH: " << s_mesh.solve.message << "; TetGen: "
         << s_tg.solve.message << ")\n";

  nlohmann::json& record = check.record;
  record = run_record_common(progress, cmd);
  record["inputs"] = inputs;
  record["config"] = {{"source", config.source}, {"effective_yaml", config.to_yaml()}};
  record["tetgen"] = {{"version", "1.5 (Debian libtet1.5)"},
                      {"switches", tg.switches},
                      {"sizing", sizing},
                      {"steiner_points", tg.steiner_points},
                      {"unseeded_tets", {{"tets", tg.unseeded.tets}, {"groups", tg.unseeded.groups},
                                         {"volume_mm3", tg.unseeded.volume_mm3}}},
                      {"input_triangles", surface.triangles.size()},
                      {"radius_edge_ratio_bound", bound},
                      {"tets_above_radius_edge_bound", above_tg.above},
                      {"mesh_tets_above_radius_edge_bound", above_mesh.above},
                      {"tets_above_radius_edge_bound_account", {{"tetgen", account_json(above_tg)}, {"mesh", account_json(above_mesh)}}},
                      {"radius_edge_ratio_forced_by_input", forced_json(forced, surface, mesh)},
                      {"mesh", out.final_path("mesh_tetgen.vtu").string()}};
  record["tissues"] = tissues;
  record["interfaces"] = interfaces;
  record["conformity"] = {{"mesh", to_json(c_mesh)}, {"tetgen", to_json(c_tg)}};
  record["max_volume_difference_percent"] = check.max_volume_difference_percent;
  record["target"] = {{"tissue", target},
                      {"mesh_mean_displacement_mm", vec_json(d_mesh)},
                      {"tetgen_mean_displacement_mm", vec_json(d_tg)},
                      {"difference_percent", check.target_displacement_difference_percent},
                      {"mesh_solve", {{"converged", s_mesh.solve.converged}, {"message", s_mesh.solve.message}}},
                      {"tetgen_solve", {{"converged", s_tg.solve.converged}, {"message", s_tg.solve.message}}}};
  write_text_file(out.stage("check.json"), record.dump(2) + "\n");
  std::cout << text.str();
  return check;
}

}  // namespace tissuemesh::app
