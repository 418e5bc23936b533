// The plots of report.html, from a mesh and from the JSON records the commands write (report.json,
// solve.json, prone2supine.json, summary.json): what each chart shows and in which units is in
// its title and axis titles. Records missing a key simply give no chart.
#pragma once

#include "core/tet_mesh.h"
#include "report/html_report.h"

#include <nlohmann/json.hpp>

#include <string>

namespace tissuemesh {

/// Dihedral-angle (5 degree bins) and radius-ratio (0.05 bins) histograms of `mesh`, bars stacked
/// by tissue in the tissues' colours; every tet counts its six angles.
void add_quality_charts(HtmlReport& report, const TetMesh& mesh);

/// From a mesh run's record: per-tissue volume error against the voxel volume (%), and for the
/// surface pipeline its Table 1 triangle-quality figures against those of Alqaoud et al. ("Multi-
/// material, approach-guided, controlled-resolution breast meshing"), 21K and 2.1K cases.
void add_mesh_record_charts(HtmlReport& report, const nlohmann::json& record);

/// From a solve record: the Newton residual norm of every iteration (log scale), by increment.
/// `id` keeps several solves in one page apart.
void add_solve_record_charts(HtmlReport& report, const nlohmann::json& record, const std::string& id,
                             const std::string& title);

/// From a prone2supine record: the reference-state iteration's shape mismatch per forward solve.
void add_prone2supine_record_charts(HtmlReport& report, const nlohmann::json& record);

/// From a sweep's summary.json: per output, its standardised regression coefficients on each
/// parameter and, for a Sobol' design, the first-order and total indices.
void add_sweep_summary_charts(HtmlReport& report, const nlohmann::json& summary);

/// Time per stage (horizontal bars, s) of a record's "timings".
void add_timing_chart(HtmlReport& report, const nlohmann::json& record, const std::string& id,
                      const std::string& title);

}  // namespace tissuemesh
