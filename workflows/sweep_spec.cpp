#include "workflows/sweep_spec.h"

#include "core/errors.h"
#include "core/quantity.h"
#include "core/yaml_map.h"
#include "workflows/sweep_parameters.h"

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <filesystem>
#include <set>

namespace tissuemesh {

namespace {

/// A value of parameter `path`: a quantity of its dimension, or a plain number (nu, ratios).
double read_value(const YAML::Node& node, const std::string& path, bool ratio, const std::string& where) {
  if (!node.IsScalar()) throw InputError(where + ": expected a value");
  Dimension dim;
  if (!ratio && parameter_dimension(path, dim)) return parse_quantity(node.Scalar(), dim, where);
  try {
    const double v = node.as<double>();
    if (!std::isfinite(v)) throw InputError(where + ": not a finite number");
    return v;
  } catch (const YAML::Exception&) {
    throw InputError(where + ": expected a plain number, got '" + node.Scalar() + "'");
  }
}

SweepParameter read_parameter(YamlMap& m, const std::string& path) {
  SweepParameter p;
  p.path = path;
  Dimension unused;
  parameter_dimension(path, unused);  // an unknown path is an error here already
  p.ratio_to = m.text("ratio_to", "");
  const bool ratio = !p.ratio_to.empty();
  const bool range = m.has("range"), values = m.has("values");
  if (range == values) throw InputError(m.here() + "give exactly one of `range: [min, max]` and `values: [...]`");
  if (range) {
    const YAML::Node r = m.raw("range");
    if (!r.IsSequence() || r.size() != 2) throw InputError(m.where("range") + ": expected [min, max]");
    p.has_range = true;
    p.lo = read_value(r[0], path, ratio, m.where("range") + "[0]");
    p.hi = read_value(r[1], path, ratio, m.where("range") + "[1]");
    if (!(p.lo <= p.hi)) throw InputError(m.where("range") + ": min > max");
    const std::string scale = m.text("scale", "linear");
    if (scale == "log") {
      p.scale = ParameterScale::Log;
      if (!(p.lo > 0.0)) throw InputError(m.where("scale") + ": a log scale needs min > 0");
    } else if (scale != "linear") {
      throw InputError(m.where("scale") + ": unknown scale '" + scale + "' (linear or log)");
    }
  } else {
    const YAML::Node v = m.raw("values");
    if (!v.IsSequence() || v.size() == 0) throw InputError(m.where("values") + ": expected a non-empty list");
    for (std::size_t i = 0; i < v.size(); ++i)
      p.values.push_back(read_value(v[i], path, ratio, m.where("values") + "[" + std::to_string(i) + "]"));
  }
  m.finish();
  return p;
}

}  // namespace

const char* design_name(DesignType d) {
  switch (d) {
    case DesignType::Grid: return "grid";
    case DesignType::Lhs: return "lhs";
    case DesignType::Sobol: return "sobol";
    case DesignType::Table: return "table";
  }
  return "?";
}

SweepSpec SweepSpec::load(const std::string& path) {
  SweepSpec s;
  s.source = path;
  YamlMap top(load_yaml_file(path), "", path);
  YamlMap params = top.map("parameters");
  const std::vector<std::string> paths = params.keys();
  if (paths.empty()) throw InputError(path + ": parameters: at least one parameter is needed");
  std::set<std::string> seen;
  for (const std::string& p : paths) {
    if (!seen.insert(p).second) throw InputError(params.where(p) + ": given twice");
    YamlMap m = params.map(p);
    s.parameters.push_back(read_parameter(m, p));
  }
  params.finish();
  for (const SweepParameter& p : s.parameters) {
    if (p.ratio_to.empty()) continue;
    const SweepParameter* target = nullptr;
    for (const SweepParameter& q : s.parameters)
      if (q.path == p.ratio_to) target = &q;
    if (!target)
      throw InputError(path + ": parameters." + p.path + ".ratio_to: '" + p.ratio_to +
                       "' is not a parameter of this sweep");
    if (!target->ratio_to.empty())
      throw InputError(path + ": parameters." + p.path + ".ratio_to: '" + p.ratio_to + "' is tied itself");
  }
  YamlMap design = top.map("design");
  const std::string type = design.text("type", "lhs");
  if (type == "grid") s.design = DesignType::Grid;
  else if (type == "lhs") s.design = DesignType::Lhs;
  else if (type == "sobol") s.design = DesignType::Sobol;
  else if (type == "table") s.design = DesignType::Table;
  else throw InputError(design.where("type") + ": unknown design '" + type + "' (grid, lhs, sobol or table)");
  s.levels = design.integer("levels", s.levels);
  if (s.levels < 1 || s.levels > 100) throw InputError(design.where("levels") + ": must be in [1, 100]");
  s.samples = design.integer("samples", s.samples);
  if (s.samples < 1 || s.samples > 1000000) throw InputError(design.where("samples") + ": must be in [1, 1000000]");
  const int seed = design.integer("seed", 1);
  if (seed < 0) throw InputError(design.where("seed") + ": must be >= 0");
  s.seed = static_cast<std::uint64_t>(seed);
  s.table_file = design.text("file", "");
  if (s.design == DesignType::Table) {
    if (s.table_file.empty()) throw InputError(design.where("file") + ": a table design needs its CSV file");
    const std::filesystem::path f(s.table_file);
    if (f.is_relative()) s.table_file = (std::filesystem::path(path).parent_path() / f).string();
  }
  design.finish();
  s.analysis = top.text("analysis", s.analysis);
  if (s.analysis != "solve" && s.analysis != "prone2supine")
    throw InputError(top.where("analysis") + ": unknown analysis '" + s.analysis + "' (solve or prone2supine)");
  s.save_fields = top.boolean("save_fields", false);
  if (s.analysis == "prone2supine" && top.has("export"))
    throw InputError(top.where("export") + ": not available with analysis prone2supine (use `tissuemesh prone2supine` "
                                           "on a sample's config for its supine models)");
  if (top.has("export")) {
    const YAML::Node e = top.raw("export");
    if (!e.IsSequence()) throw InputError(top.where("export") + ": expected a list of formats");
    for (const auto& f : e) {
      const std::string name = f.Scalar();
      if (name != "febio" && name != "abaqus" && name != "sofa")
        throw InputError(top.where("export") + ": unknown format '" + name + "' (febio, abaqus, sofa)");
      s.exports.push_back(name);
    }
  }
  top.finish();
  return s;
}

std::string SweepSpec::to_yaml() const {
  YAML::Emitter out;
  out.SetDoublePrecision(15);
  out << YAML::BeginMap << YAML::Key << "parameters" << YAML::Value << YAML::BeginMap;
  for (const SweepParameter& p : parameters) {
    Dimension dim;
    const bool with_unit = p.ratio_to.empty() && parameter_dimension(p.path, dim);
    auto value = [&](double v) { return with_unit ? format_quantity(v, dim) : YAML::Dump(YAML::Node(v)); };
    out << YAML::Key << p.path << YAML::Value << YAML::Flow << YAML::BeginMap;
    if (!p.ratio_to.empty()) out << YAML::Key << "ratio_to" << YAML::Value << p.ratio_to;
    if (p.has_range) {
      out << YAML::Key << "range" << YAML::Value << YAML::Flow << YAML::BeginSeq << value(p.lo) << value(p.hi)
          << YAML::EndSeq;
      out << YAML::Key << "scale" << YAML::Value << (p.scale == ParameterScale::Log ? "log" : "linear");
    } else {
      out << YAML::Key << "values" << YAML::Value << YAML::Flow << YAML::BeginSeq;
      for (double v : p.values) out << value(v);
      out << YAML::EndSeq;
    }
    out << YAML::EndMap;
  }
  out << YAML::EndMap;
  out << YAML::Key << "design" << YAML::Value << YAML::Flow << YAML::BeginMap << YAML::Key << "type" << YAML::Value
      << design_name(design) << YAML::Key << "levels" << YAML::Value << levels << YAML::Key << "samples"
      << YAML::Value << samples << YAML::Key << "seed" << YAML::Value << seed;
  if (design == DesignType::Table) out << YAML::Key << "file" << YAML::Value << table_file;
  out << YAML::EndMap;
  out << YAML::Key << "analysis" << YAML::Value << analysis;
  out << YAML::Key << "save_fields" << YAML::Value << save_fields;
  out << YAML::Key << "export" << YAML::Value << YAML::Flow << YAML::BeginSeq;
  for (const std::string& e : exports) out << e;
  out << YAML::EndSeq << YAML::EndMap;
  return std::string(out.c_str()) + "\n";
}

}  // namespace tissuemesh
