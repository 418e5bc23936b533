// Parts of a run's report that both pipelines write alike (pipeline/mesh_report.h for the direct
// pipeline, pipeline/surface_report.h for the surface pipeline): the sliver repair's counts,
// the absorbed islands per tissue, and the tissues outside the volume tolerance, as JSON and as
// text lines. Volumes in mm^3.
#pragma once

#include "image/small_islands.h"
#include "pipeline/mesh_checks.h"
#include "volume/mesh3_optimisation.h"
#include "volume/tet_volume_restoration.h"

#include <nlohmann/json.hpp>

#include <map>
#include <string>
#include <vector>

namespace tissuemesh::report_parts {

/// printf of up to three numbers into a string (at most 159 characters).
std::string fmt(const char* format, double a, double b = 0, double c = 0);

/// The sliver repair's steps into `j` (boundary slivers, flips, smoothing, offsets, splits,
/// boundary pinches per tissue, named by `tissues`), and the same as text lines.
void add_sliver_repair_json(nlohmann::json& j, const SliverRepair& repair, const std::vector<std::string>& tissues);
std::string sliver_repair_text(const SliverRepair& repair);

/// Islands given to their surroundings: per tissue (named by `names`, tissue id 1 = names[0],
/// 0 = outside) the components, voxels and volume, and where the voxels went; and the tissues kept
/// whole although under the threshold.
nlohmann::json islands_json(const IslandAbsorption& a, const std::vector<std::string>& names);
std::string islands_text(const IslandAbsorption& a, const std::vector<std::string>& names);

/// Names of the tissues a restoration released (at least 1 % off and brought less than a tenth of
/// the way by a round), and the same as a text fragment ("; released …", empty when none).
std::vector<std::string> released_names(const VolumeRestoration& r, const std::vector<std::string>& names);
std::string released_text(const VolumeRestoration& r, const std::vector<std::string>& names);

/// The tets' volume restoration: rounds, nodes moved and held, largest move, and each tissue's
/// volume error against `voxel_mm3` (tissue id -> mm^3) before it, percent; as JSON and as one
/// text line.
nlohmann::json tet_restoration_json(const TetVolumeRestoration& t, const std::map<int, double>& voxel_mm3,
                                    const std::vector<std::string>& names);
std::string tet_restoration_text(const TetVolumeRestoration& t, const std::map<int, double>& voxel_mm3,
                                 const std::vector<std::string>& names);

/// Tissues whose meshed volume is outside the tolerance: name, volume, reference, error percent.
nlohmann::json deviations_json(const std::vector<VolumeDeviation>& deviations);

}  // namespace tissuemesh::report_parts
