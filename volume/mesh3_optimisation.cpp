#include "volume/mesh3_optimisation.h"

namespace tissuemesh {

void Mesh3Optimisation::read(YamlMap& m) {
  lloyd = m.boolean("lloyd", lloyd);
  odt = m.boolean("odt", odt);
  optimise_time_limit_s = m.positive("optimise_time_limit_s", optimise_time_limit_s);
  perturb = m.boolean("perturb", perturb);
  exude = m.boolean("exude", exude);
  sliver_bound_deg = m.in_range("sliver_bound_deg", sliver_bound_deg, 0.0, 60.0);
  sliver_time_limit_s = m.positive("sliver_time_limit_s", sliver_time_limit_s);
  remove_boundary_slivers_deg = m.in_range("remove_boundary_slivers_deg", remove_boundary_slivers_deg, 0.0, 30.0);
  flip_slivers_below_deg = m.in_range("flip_slivers_below_deg", flip_slivers_below_deg, 0.0, 60.0);
  interface_flips = m.boolean("interface_flips", interface_flips);
  split_relabels = interface_flips;
  smooth_slivers_below_deg = m.in_range("smooth_slivers_below_deg", smooth_slivers_below_deg, 0.0, 60.0);
  smooth_near_planar_deg = m.in_range("smooth_near_planar_deg", smooth_near_planar_deg, 0.0, 30.0);
  sliver_offset_edge_ratio = m.in_range("sliver_offset_edge_ratio", sliver_offset_edge_ratio, 0.0, 0.5);
  open_boundary_pinches = m.boolean("open_boundary_pinches", open_boundary_pinches);
}

void Mesh3Optimisation::emit(YAML::Emitter& out) const {
  out << YAML::Key << "lloyd" << YAML::Value << lloyd;
  out << YAML::Key << "odt" << YAML::Value << odt;
  out << YAML::Key << "optimise_time_limit_s" << YAML::Value << optimise_time_limit_s;
  out << YAML::Key << "perturb" << YAML::Value << perturb;
  out << YAML::Key << "exude" << YAML::Value << exude;
  out << YAML::Key << "sliver_bound_deg" << YAML::Value << sliver_bound_deg;
  out << YAML::Key << "sliver_time_limit_s" << YAML::Value << sliver_time_limit_s;
  out << YAML::Key << "remove_boundary_slivers_deg" << YAML::Value << remove_boundary_slivers_deg;
  out << YAML::Key << "flip_slivers_below_deg" << YAML::Value << flip_slivers_below_deg;
  out << YAML::Key << "interface_flips" << YAML::Value << interface_flips;
  out << YAML::Key << "smooth_slivers_below_deg" << YAML::Value << smooth_slivers_below_deg;
  out << YAML::Key << "smooth_near_planar_deg" << YAML::Value << smooth_near_planar_deg;
  out << YAML::Key << "sliver_offset_edge_ratio" << YAML::Value << sliver_offset_edge_ratio;
  out << YAML::Key << "open_boundary_pinches" << YAML::Value << open_boundary_pinches;
}

}  // namespace tissuemesh
