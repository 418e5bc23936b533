// Why: `auto` picks tet10 from nu >= 0.49 on because tet4 locks as nu -> 0.5: with nearly
// incompressible tissue a tet4 model sags far less under gravity than the tet10 model of the same
// mesh (docs/solver.md, "Elements"). The demo nevertheless asks for tet4 explicitly: its CalculiX
// cross-check takes minutes as tet4 and would take hours as tet10.
#include "core/model_settings.h"

#include "core/errors.h"
#include "core/quantity.h"

#include <cmath>
#include <sstream>

namespace tissuemesh {

namespace {

InterfaceSide parse_side(const YAML::Node& node, const std::string& where) {
  InterfaceSide side;
  auto add = [&](const YAML::Node& n) {
    if (!n.IsScalar()) throw InputError(where + ": expected a tissue name or 'outside'");
    if (n.Scalar() == "outside")
      side.outside = true;
    else
      side.tissues.push_back(n.Scalar());
  };
  if (node.IsSequence())
    for (const YAML::Node& n : node) add(n);
  else
    add(node);
  if (side.tissues.empty() && !side.outside) throw InputError(where + ": an interface side names no tissue");
  return side;
}

SetSelection parse_selection(YamlMap& entry) {
  SetSelection s;
  int given = 0;
  if (entry.has("between")) {
    ++given;
    s.kind = SetSelection::Kind::Between;
    YAML::Node sides = entry.raw("between");
    if (!sides.IsSequence() || sides.size() != 2)
      throw InputError(entry.where("between") + ": expected two sides [A, B], each a tissue name, a list of "
                                                "names, or 'outside'");
    s.side_a = parse_side(sides[0], entry.where("between"));
    s.side_b = parse_side(sides[1], entry.where("between"));
  }
  if (entry.has("plane")) {
    ++given;
    s.kind = SetSelection::Kind::Plane;
    YamlMap plane = entry.map("plane");
    s.plane_point_mm = plane.vector3("point_mm", s.plane_point_mm);
    const Eigen::Vector3d n = plane.vector3("normal", s.plane_normal);
    if (!(n.norm() > 0)) throw InputError(plane.where("normal") + ": must not be the zero vector");
    s.plane_normal = n.normalized();
    s.plane_tolerance_mm = plane.positive("tolerance_mm", s.plane_tolerance_mm);
    plane.finish();
  }
  if (entry.has("box_mm")) {
    ++given;
    s.kind = SetSelection::Kind::Box;
    YAML::Node box = entry.raw("box_mm");
    if (!box.IsSequence() || box.size() != 6)
      throw InputError(entry.where("box_mm") + ": expected [xmin, ymin, zmin, xmax, ymax, zmax]");
    for (int i = 0; i < 6; ++i) {
      double v = 0.0;
      try {
        v = box[i].as<double>();
      } catch (const YAML::Exception&) {
        throw InputError(entry.where("box_mm") + ": expected 6 numbers, got '" + YAML::Dump(box[i]) + "'");
      }
      if (!std::isfinite(v)) throw InputError(entry.where("box_mm") + ": values must be finite");
      (i < 3 ? s.box_min_mm[i] : s.box_max_mm[i - 3]) = v;
    }
    if (!(s.box_min_mm.array() <= s.box_max_mm.array()).all())
      throw InputError(entry.where("box_mm") + ": min must not exceed max");
  }
  if (given != 1)
    throw InputError(entry.here() + "give exactly one of `between`, `plane`, `box_mm` (got " +
                     std::to_string(given) + ")");
  return s;
}

void selection_to_yaml(const SetSelection& s, YAML::Emitter& out) {
  auto side = [&](const InterfaceSide& x) {
    if (x.tissues.size() == 1 && !x.outside)
      out << x.tissues.front();
    else if (x.tissues.empty())
      out << "outside";
    else {
      out << YAML::Flow << YAML::BeginSeq;
      for (const auto& t : x.tissues) out << t;
      if (x.outside) out << "outside";
      out << YAML::EndSeq;
    }
  };
  auto vec = [&](const Eigen::Vector3d& v) {
    out << YAML::Flow << YAML::BeginSeq << v[0] << v[1] << v[2] << YAML::EndSeq;
  };
  switch (s.kind) {
    case SetSelection::Kind::Between:
      out << YAML::Key << "between" << YAML::Value << YAML::Flow << YAML::BeginSeq;
      side(s.side_a);
      side(s.side_b);
      out << YAML::EndSeq;
      break;
    case SetSelection::Kind::Plane:
      out << YAML::Key << "plane" << YAML::Value << YAML::Flow << YAML::BeginMap << YAML::Key << "point_mm"
          << YAML::Value;
      vec(s.plane_point_mm);
      out << YAML::Key << "normal" << YAML::Value;
      vec(s.plane_normal);
      out << YAML::Key << "tolerance_mm" << YAML::Value << s.plane_tolerance_mm << YAML::EndMap;
      break;
    case SetSelection::Kind::Box:
      out << YAML::Key << "box_mm" << YAML::Value << YAML::Flow << YAML::BeginSeq;
      for (int i = 0; i < 3; ++i) out << s.box_min_mm[i];
      for (int i = 0; i < 3; ++i) out << s.box_max_mm[i];
      out << YAML::EndSeq;
      break;
  }
}

std::string sides_text(const InterfaceSide& x) {
  std::string out;
  for (const auto& t : x.tissues) out += (out.empty() ? "" : ",") + t;
  if (x.outside) out += (out.empty() ? "" : ",") + std::string("outside");
  return out;
}

}  // namespace

std::string SetSelection::describe() const {
  std::ostringstream s;
  switch (kind) {
    case Kind::Between: s << "interface " << sides_text(side_a) << "|" << sides_text(side_b); break;
    case Kind::Plane:
      s << "plane through (" << plane_point_mm.transpose() << ") mm, normal (" << plane_normal.transpose()
        << "), tolerance " << plane_tolerance_mm << " mm";
      break;
    case Kind::Box: s << "box (" << box_min_mm.transpose() << ")-(" << box_max_mm.transpose() << ") mm"; break;
  }
  return s.str();
}

ElementOrder default_element(const std::vector<MaterialSpec>& materials) {
  for (const MaterialSpec& m : materials)
    if (m.poisson_ratio() >= 0.49) return ElementOrder::Quadratic;
  return ElementOrder::Linear;
}

ModelSettings ModelSettings::phantom_default() {
  ModelSettings s;
  s.element = ElementOrder::Linear;
  NodeSetSettings wall;
  wall.name = "chest_wall";
  wall.selection.side_a.tissues = {"muscle"};
  wall.selection.side_b.outside = true;
  s.node_sets.push_back(wall);
  FaceSetSettings skin;
  skin.name = "skin_surface";
  skin.selection.side_a.tissues = {"skin"};
  skin.selection.side_b.outside = true;
  s.face_sets.push_back(skin);
  return s;
}

ModelSettings ModelSettings::from_yaml(YamlMap& map) {
  ModelSettings s;
  s.units = parse_unit_system(map.text("units", unit_system_name(s.units)));
  const std::string element = map.text("element", "auto");
  if (element == "tet4")
    s.element = ElementOrder::Linear;
  else if (element == "tet10")
    s.element = ElementOrder::Quadratic;
  else if (element != "auto")
    throw InputError(map.where("element") + ": unknown element '" + element + "' (tet4, tet10 or auto)");
  const std::string node_order = map.text("node_order", "rcm");
  if (node_order == "rcm")
    s.node_order = NodeOrder::ReverseCuthillMcKee;
  else if (node_order == "mesh")
    s.node_order = NodeOrder::Mesh;
  else
    throw InputError(map.where("node_order") + ": unknown node order '" + node_order +
                     "' (rcm: reverse Cuthill-McKee, or mesh: the mesh's order)");

  YAML::Node sets = map.raw("node_sets");
  if (sets.IsDefined() && !sets.IsNull()) {
    if (!sets.IsSequence()) throw InputError(map.where("node_sets") + ": expected a list");
    for (std::size_t i = 0; i < sets.size(); ++i) {
      YamlMap entry(sets[i], "model.node_sets[" + std::to_string(i) + "]", map.source());
      NodeSetSettings n;
      n.name = entry.required_text("name");
      n.selection = parse_selection(entry);
      const std::string c = entry.text("constraint", "fixed");
      if (c == "fixed")
        n.constraint = Constraint::Fixed;
      else if (c == "sliding")
        n.constraint = Constraint::Sliding;
      else
        throw InputError(entry.where("constraint") + ": unknown constraint '" + c + "' (fixed or sliding)");
      entry.finish();
      s.node_sets.push_back(n);
    }
  }
  YAML::Node faces = map.raw("face_sets");
  if (faces.IsDefined() && !faces.IsNull()) {
    if (!faces.IsSequence()) throw InputError(map.where("face_sets") + ": expected a list");
    for (std::size_t i = 0; i < faces.size(); ++i) {
      YamlMap entry(faces[i], "model.face_sets[" + std::to_string(i) + "]", map.source());
      FaceSetSettings f;
      f.name = entry.required_text("name");
      f.selection = parse_selection(entry);
      entry.finish();
      s.face_sets.push_back(f);
    }
  }

  YamlMap gravity = map.map("gravity");
  s.gravity = GravitySettings::from_yaml(gravity, GravitySettings());

  YamlMap a = map.map("analysis");
  AnalysisSettings& an = s.analysis;
  an.load_steps = a.integer("load_steps", an.load_steps);
  an.max_load_steps = a.integer("max_load_steps", an.max_load_steps);
  an.min_step_fraction = a.in_range("min_step_fraction", an.min_step_fraction, 1e-12, 1.0);
  an.max_newton_iterations = a.integer("max_newton_iterations", an.max_newton_iterations);
  an.displacement_tolerance = a.in_range("displacement_tolerance", an.displacement_tolerance, 1e-16, 1.0);
  an.energy_tolerance = a.in_range("energy_tolerance", an.energy_tolerance, 0.0, 1.0);
  an.residual_tolerance = a.in_range("residual_tolerance", an.residual_tolerance, 0.0, 1.0);
  if (a.has("tet4_pressure")) {
    const std::string v = a.text("tet4_pressure", "");
    if (v != "element" && v != "nodal")
      throw InputError(a.where("tet4_pressure") + ": unknown value '" + v +
                       "' (element: standard tet4, as exported | nodal: average nodal pressure, built-in solver only)");
    an.tet4_pressure = v == "nodal" ? Tet4Pressure::Nodal : Tet4Pressure::Element;
  }
  if (an.load_steps < 1 || an.load_steps > 10000)
    throw InputError(a.where("load_steps") + ": must be in [1, 10000]");
  if (an.max_load_steps < an.load_steps)
    throw InputError(a.where("max_load_steps") + ": must be >= load_steps (" + std::to_string(an.load_steps) + ")");
  if (an.max_newton_iterations < 1) throw InputError(a.where("max_newton_iterations") + ": must be >= 1");
  a.finish();
  map.finish();
  return s;
}

void ModelSettings::to_yaml(YAML::Emitter& out) const {
  out << YAML::BeginMap;
  out << YAML::Key << "units" << YAML::Value << unit_system_name(units);
  out << YAML::Key << "element" << YAML::Value
      << (!element ? "auto" : *element == ElementOrder::Linear ? "tet4" : "tet10");
  out << YAML::Key << "node_order" << YAML::Value << (node_order == NodeOrder::Mesh ? "mesh" : "rcm");
  out << YAML::Key << "node_sets" << YAML::Value << YAML::BeginSeq;
  for (const NodeSetSettings& n : node_sets) {
    out << YAML::Flow << YAML::BeginMap << YAML::Key << "name" << YAML::Value << n.name;
    selection_to_yaml(n.selection, out);
    out << YAML::Key << "constraint" << YAML::Value << (n.constraint == Constraint::Fixed ? "fixed" : "sliding")
        << YAML::EndMap;
  }
  out << YAML::EndSeq;
  out << YAML::Key << "face_sets" << YAML::Value << YAML::BeginSeq;
  for (const FaceSetSettings& f : face_sets) {
    out << YAML::Flow << YAML::BeginMap << YAML::Key << "name" << YAML::Value << f.name;
    selection_to_yaml(f.selection, out);
    out << YAML::EndMap;
  }
  out << YAML::EndSeq;
  out << YAML::Key << "gravity" << YAML::Value;
  gravity.to_yaml(out);
  const AnalysisSettings& a = analysis;
  out << YAML::Key << "analysis" << YAML::Value << YAML::Flow << YAML::BeginMap;
  out << YAML::Key << "load_steps" << YAML::Value << a.load_steps;
  out << YAML::Key << "max_load_steps" << YAML::Value << a.max_load_steps;
  out << YAML::Key << "min_step_fraction" << YAML::Value << a.min_step_fraction;
  out << YAML::Key << "max_newton_iterations" << YAML::Value << a.max_newton_iterations;
  out << YAML::Key << "displacement_tolerance" << YAML::Value << a.displacement_tolerance;
  out << YAML::Key << "energy_tolerance" << YAML::Value << a.energy_tolerance;
  out << YAML::Key << "residual_tolerance" << YAML::Value << a.residual_tolerance;
  out << YAML::Key << "tet4_pressure" << YAML::Value << (a.tet4_pressure == Tet4Pressure::Nodal ? "nodal" : "element");
  out << YAML::EndMap;
  out << YAML::EndMap;
}


}  // namespace tissuemesh
