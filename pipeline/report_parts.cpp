// The parts of a run's report that both pipelines share (pipeline/report_parts.h).
#include "pipeline/report_parts.h"

#include <cstdio>
#include <utility>
#include <sstream>

namespace tissuemesh::report_parts {

std::string fmt(const char* format, double a, double b, double c) {
  char buf[160];
  std::snprintf(buf, sizeof buf, format, a, b, c);
  return buf;
}

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

namespace {

std::string tissue_name(int id, const std::vector<std::string>& names) {
  if (id == 0) return "outside";
  return id > 0 && static_cast<std::size_t>(id) <= names.size() ? names[id - 1] : "tissue " + std::to_string(id);
}

}  // namespace

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

namespace {

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

std::vector<std::string> released_names(const VolumeRestoration& r, const std::vector<std::string>& names) {
  std::vector<std::string> out;
  for (int id : r.released) out.push_back(id >= 1 && id <= static_cast<int>(names.size()) ? names[id - 1] : std::to_string(id));
  return out;
}

std::string released_text(const VolumeRestoration& r, const std::vector<std::string>& names) {
  if (r.released.empty()) return "";
  std::string o = "; released (not restorable by offsets, no longer moved):";
  for (const std::string& n : released_names(r, names)) o += " " + n;
  return o;
}

nlohmann::json tet_restoration_json(const TetVolumeRestoration& t, const std::map<int, double>& voxel_mm3,
                                    const std::vector<std::string>& names) {
  return {{"rounds", t.offsets.rounds},
          {"nodes_moved", t.nodes_moved},
          {"max_offset_mm", t.max_offset_mm},
          {"nodes_held", t.offsets.frozen_vertices},
          {"stopped_early", t.offsets.stopped_early},
          {"tissues_released", released_names(t.offsets, names)},
          {"volume_error_percent_before", errors_before_restoration(t, voxel_mm3, names)}};
}

std::string tet_restoration_text(const TetVolumeRestoration& t, const std::map<int, double>& voxel_mm3,
                                 const std::vector<std::string>& names) {
  std::ostringstream o;
  o << "tet volume restoration: " << t.offsets.rounds << " rounds of patch offsets moved " << t.nodes_moved
    << " boundary and interface nodes, largest move " << fmt("%.3f", t.max_offset_mm) << " mm";
  if (t.offsets.frozen_vertices > 0)
    o << "; " << t.offsets.frozen_vertices << " nodes held where a round would have flattened a tet";
  o << released_text(t.offsets, names);
  o << "; before it";
  for (const auto& [name, percent] : errors_before_restoration(t, voxel_mm3, names))
    o << " " << name << fmt(" %+.2f %%", percent);
  o << "\n";
  return o.str();
}

nlohmann::json deviations_json(const std::vector<VolumeDeviation>& deviations) {
  nlohmann::json out = nlohmann::json::array();
  for (const VolumeDeviation& d : deviations)
    out.push_back({{"tissue", d.tissue}, {"volume_mm3", d.volume_mm3},
                   {"reference_volume_mm3", d.reference_volume_mm3}, {"error_percent", d.error_percent}});
  return out;
}

}  // namespace tissuemesh::report_parts
