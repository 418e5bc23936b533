#include "app/gmsh_check.h"

#include "app/check_outputs.h"
#include "app/cli_support.h"
#include "fe_export/gmsh/gmsh_quality.h"
#include "quality/mesh_quality.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <limits>
#include <sstream>
#include <vector>

namespace tissuemesh::app {

namespace {

// Minimum and mean of one measure over one tissue, by us and by Gmsh.
struct Pair {
  double min_ours = std::numeric_limits<double>::infinity(), min_gmsh = min_ours;
  double sum_ours = 0, sum_gmsh = 0;
  void add(double ours, double gmsh) {
    min_ours = std::min(min_ours, ours);
    min_gmsh = std::min(min_gmsh, gmsh);
    sum_ours += ours;
    sum_gmsh += gmsh;
  }
  // Means over `tets` (> 0) tets.
  double mean_ours(std::size_t tets) const { return sum_ours / static_cast<double>(tets); }
  double mean_gmsh(std::size_t tets) const { return sum_gmsh / static_cast<double>(tets); }
  nlohmann::json json(std::size_t tets) const {
    return {{"min_ours", min_ours}, {"min_gmsh", min_gmsh}, {"mean_ours", mean_ours(tets)}, {"mean_gmsh", mean_gmsh(tets)}};
  }
};

struct TissueRow {
  std::string name;
  std::size_t tets = 0;
  Pair gamma, sicn;
  double min_dihedral_deg = std::numeric_limits<double>::infinity();
};

}  // namespace

GmshCheck gmsh_check_into(const TetMesh& mesh, const nlohmann::json& inputs, const nlohmann::json& config_record,
                          const std::string& cmd, Progress& progress, OutputDir& out) {
  GmshQuality result;
  {
    auto stage = progress.stage("Gmsh element quality");
    result = gmsh_tet_quality(mesh, out.stage("quality_gmsh.pos").string());
    stage.note(std::to_string(result.tets.size()) + " tets");
  }
  const std::vector<GmshTetQuality>& gmsh = result.tets;

  GmshCheck check;
  std::vector<TissueRow> rows(mesh.num_tissues() + 1);  // last row: all tissues
  for (std::size_t t = 0; t < mesh.num_tissues(); ++t) rows[t].name = mesh.tissue_names[t];
  rows.back().name = "all tissues";
  for (std::size_t e = 0; e < mesh.tets.size(); ++e) {
    const auto& k = mesh.tets[e];
    const TetShape s = tet_shape(mesh.points[k[0]], mesh.points[k[1]], mesh.points[k[2]], mesh.points[k[3]]);
    check.max_gamma_difference = std::max(check.max_gamma_difference, std::abs(gmsh[e].gamma - s.radius_ratio));
    check.max_sicn_difference = std::max(check.max_sicn_difference, std::abs(gmsh[e].sicn - s.sicn));
    const double min_dihedral = *std::min_element(s.dihedral_deg.begin(), s.dihedral_deg.end());
    for (TissueRow* row : {&rows[static_cast<std::size_t>(mesh.tissue_ids[e] - 1)], &rows.back()}) {
      ++row->tets;
      row->gamma.add(s.radius_ratio, gmsh[e].gamma);
      row->sicn.add(s.sicn, gmsh[e].sicn);
      row->min_dihedral_deg = std::min(row->min_dihedral_deg, min_dihedral);
    }
  }
  check.agree = check.max_gamma_difference <= kGmshPrintedDigitsAbs && check.max_sicn_difference <= kGmshPrintedDigitsAbs;

  std::ostringstream text;
  char line[256];
  text << "\nGmsh " << result.version << " element quality against ours (gamma = radius ratio 3r/R; SICN):\n";
  std::snprintf(line, sizeof line, "  %-12s %9s %10s %10s %10s %10s %10s %10s %10s\n", "tissue", "tets", "min gamma",
                "Gmsh", "mean gamma", "Gmsh", "min SICN", "Gmsh", "min [deg]");
  text << line;
  nlohmann::json tissues = nlohmann::json::array();
  for (const TissueRow& r : rows) {
    if (r.tets == 0) continue;
    std::snprintf(line, sizeof line, "  %-12s %9zu %10.6f %10.6f %10.6f %10.6f %10.6f %10.6f %10.2f\n", r.name.c_str(),
                  r.tets, r.gamma.min_ours, r.gamma.min_gmsh, r.gamma.mean_ours(r.tets), r.gamma.mean_gmsh(r.tets),
                  r.sicn.min_ours, r.sicn.min_gmsh, r.min_dihedral_deg);
    text << line;
    tissues.push_back({{"tissue", r.name},
                       {"tets", r.tets},
                       {"gamma", r.gamma.json(r.tets)},
                       {"sicn", r.sicn.json(r.tets)},
                       {"min_dihedral_deg_ours", r.min_dihedral_deg}});
  }
  text << "  largest per-tet difference: gamma " << format_double("%.2e", check.max_gamma_difference) << ", SICN "
       << format_double("%.2e", check.max_sicn_difference) << " (Gmsh prints 6 significant digits: "
       << (check.agree ? "agree" : "DISAGREE") << ")\n";

  nlohmann::json& record = check.record;
  record = run_record_common(progress, cmd);
  record["inputs"] = inputs;
  record["config"] = config_record;
  record["gmsh"] = {{"version", result.version},
                    {"statistics", out.final_path("quality_gmsh.pos").string()},
                    {"measures", "gamma = 3 r / R; SICN = signed inverse condition number"}};
  record["tissues"] = tissues;
  record["max_gamma_difference"] = check.max_gamma_difference;
  record["max_sicn_difference"] = check.max_sicn_difference;
  record["tolerance"] = kGmshPrintedDigitsAbs;
  record["agree"] = check.agree;
  write_text_file(out.stage("check.json"), record.dump(2) + "\n");
  std::cout << text.str();
  return check;
}

}  // namespace tissuemesh::app
