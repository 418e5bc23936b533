#include "materials/material_config.h"

#include "core/errors.h"
#include "core/number_format.h"
#include "core/quantity.h"
#include "materials/elastic_constants.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <set>

namespace tissuemesh {

namespace {

namespace fs = std::filesystem;


// The parameter sets each law accepts (docs/configuration.md, "Materials").
const std::vector<std::set<std::string>>& forms_of(MaterialLaw law) {
  static const std::vector<std::set<std::string>> neo{{"E", "nu"},   {"mu", "K"},  {"mu", "lambda"}, {"mu", "nu"},
                                                      {"C10", "D1"}, {"C10", "K"}, {"c1", "k"}};
  static const std::vector<std::set<std::string>> mr{
      {"C10", "C01", "D1"}, {"C10", "C01", "K"}, {"C10", "C01", "nu"}, {"c1", "c2", "k"}};
  static const std::vector<std::set<std::string>> ogden{{"terms", "K"}, {"terms", "D1"}, {"terms", "nu"}};
  switch (law) {
    case MaterialLaw::NeoHookean:
    case MaterialLaw::CompressibleNeoHookean: return neo;
    case MaterialLaw::MooneyRivlin: return mr;
    case MaterialLaw::Ogden: return ogden;
  }
  return neo;
}

std::string join(const std::set<std::string>& keys, const char* sep) {
  std::string out;
  for (const std::string& k : keys) out += (out.empty() ? "" : sep) + k;
  return out;
}

MaterialLaw parse_law(YamlMap& map) {
  const std::string name = map.required_text("law");
  for (MaterialLaw law : {MaterialLaw::NeoHookean, MaterialLaw::CompressibleNeoHookean, MaterialLaw::MooneyRivlin,
                          MaterialLaw::Ogden})
    if (material_law_name(law) == name) return law;
  throw InputError(map.where("law") + ": unknown law '" + name +
                   "' (neo-hookean, compressible-neo-hookean, mooney-rivlin, ogden)");
}

// Wraps ElasticConstants' validation messages with the key path of the material.
template <typename F>
ElasticConstants constants(YamlMap& map, F&& make) {
  try {
    return make();
  } catch (const InputError& e) {
    throw InputError(map.here() + std::string(e.what()));
  }
}

// A relative preset path is looked up next to the config file first, then among the shipped
// configs (source tree, then the installed copy), so that a config copied out of configs/ still
// finds `materials/ucl-niftysim-invivo.yaml`.
fs::path resolve_preset(const std::string& preset, const std::string& config_path) {
  const fs::path p(preset);
  if (p.is_absolute()) return p;
  const fs::path beside = fs::path(config_path).parent_path() / p;
  if (fs::exists(beside)) return beside;
  for (const char* dir : {TISSUEMESH_SOURCE_CONFIG_DIR, TISSUEMESH_INSTALLED_CONFIG_DIR})
    if (fs::exists(fs::path(dir) / p)) return fs::path(dir) / p;
  return beside;  // load_yaml_file names it in the error
}

// Limits far wider than any tissue: soft tissue has a shear modulus of 0.1-100 kPa (bone ~100 MPa)
// and K/mu of 10-10^4. Outside them a value is a unit mistake (1e-30 Pa), or (K/mu beyond 10^6, nu
// above ~0.4999998) so nearly incompressible that the displacement-only elements lock and the
// tangent loses every digit. The lower bound leaves room for deliberately over-soft test models
// (0.05 Pa with K = 50 kPa: a prone-to-supine run that must stop unconverged).
constexpr double kMinShearPa = 1e-3, kMaxShearPa = 1e10, kMaxBulkToShear = 1e6;

void check_stiffness_range(const YamlMap& map, const MaterialSpec& m) {
  if (!(m.mu_Pa >= kMinShearPa && m.mu_Pa <= kMaxShearPa))
    throw InputError(map.here() + "shear modulus mu = " + format_quantity(m.mu_Pa, Dimension::Stress) +
                     " is outside 1 mPa - 10 GPa (soft tissue: 0.1-100 kPa); check the unit");
  if (!(m.K_Pa / m.mu_Pa <= kMaxBulkToShear))
    throw InputError(map.here() + "K/mu = " + format_double("%.3g", m.K_Pa / m.mu_Pa) + " (nu = " +
                     format_double("%.9g", (3 * m.K_Pa - 2 * m.mu_Pa) / (6 * m.K_Pa + 2 * m.mu_Pa)) +
                     ") is above 10^6: too close to incompressible for displacement elements; use nu <= 0.49999 "
                     "(K/mu = 5e4) or less");
}

}  // namespace

MaterialSpec parse_material(YamlMap& map) {
  MaterialSpec m;
  m.law = parse_law(map);
  std::set<std::string> given;
  for (const std::string& k : map.keys())
    if (k != "law" && k != "density" && k != "source") given.insert(k);
  const auto& forms = forms_of(m.law);
  if (std::find(forms.begin(), forms.end(), given) == forms.end()) {
    std::string accepted;
    for (const auto& f : forms) accepted += (accepted.empty() ? "" : " | ") + join(f, " + ");
    throw InputError(map.here() + std::string(given.empty() ? "no parameters given" : "parameters {" + join(given, ", ") + "}") +
                     " do not form one parameter set of " + material_law_name(m.law) + " (give exactly one of: " +
                     accepted + ")");
  }
  auto stress = [&](const std::string& key) { return quantity(map, key, Dimension::Stress, 0.0); };
  auto nu = [&] { return map.number("nu", 0.0); };
  const double D1 = given.count("D1") ? quantity(map, "D1", Dimension::InverseStress, 0.0) : 0.0;
  auto bulk_from = [&](double mu) -> double {  // K from K, k, D1 or nu, validated
    if (given.count("K")) return constants(map, [&] { return ElasticConstants::from_shear_bulk(mu, stress("K")); }).bulk_modulus();
    if (given.count("D1")) return constants(map, [&] { return ElasticConstants::from_neo_hooke(mu / 2, D1); }).bulk_modulus();
    return constants(map, [&] { return ElasticConstants::from_young_poisson(2 * mu * (1 + nu()), nu()); }).bulk_modulus();
  };

  if (m.law == MaterialLaw::NeoHookean || m.law == MaterialLaw::CompressibleNeoHookean) {
    ElasticConstants c = constants(map, [&] {
      if (given.count("E")) return ElasticConstants::from_young_poisson(stress("E"), nu());
      if (given.count("lambda")) return ElasticConstants::from_lame(stress("mu"), stress("lambda"));
      if (given.count("c1")) return ElasticConstants::from_shear_bulk(2 * stress("c1"), stress("k"));
      const double mu = given.count("mu") ? stress("mu") : 2 * stress("C10");
      if (given.count("nu")) return ElasticConstants::from_young_poisson(2 * mu * (1 + nu()), nu());
      if (given.count("D1")) return ElasticConstants::from_neo_hooke(mu / 2, D1);
      return ElasticConstants::from_shear_bulk(mu, stress("K"));
    });
    m.mu_Pa = c.shear_modulus();
    m.K_Pa = c.bulk_modulus();
    m.C10_Pa = m.mu_Pa / 2;
  } else if (m.law == MaterialLaw::MooneyRivlin) {
    if (given.count("c1")) {
      ElasticConstants c = constants(map, [&] { return ElasticConstants::from_mooney_rivlin(stress("c1"), stress("c2"), stress("k")); });
      m.C10_Pa = stress("c1");
      m.C01_Pa = stress("c2");
      m.mu_Pa = c.shear_modulus();
      m.K_Pa = c.bulk_modulus();
    } else {
      m.C10_Pa = stress("C10");
      m.C01_Pa = stress("C01");
      m.mu_Pa = 2 * (m.C10_Pa + m.C01_Pa);
      if (!(m.mu_Pa > 0))
        throw InputError(map.here() + "C10 + C01 must be positive (initial shear modulus 2 (C10 + C01))");
      m.K_Pa = bulk_from(m.mu_Pa);
    }
  } else {
    YAML::Node terms = map.raw("terms");
    if (!terms.IsSequence() || terms.size() < 1 || terms.size() > 3)
      throw InputError(map.where("terms") + ": expected a list of 1 to 3 terms [{mu: ..., alpha: ...}]");
    for (std::size_t i = 0; i < terms.size(); ++i) {
      YamlMap t(terms[i], map.path() + ".terms[" + std::to_string(i) + "]", map.source());
      OgdenTerm term;
      term.mu_Pa = quantity(t, "mu", Dimension::Stress, 0.0);
      if (!t.has("alpha")) throw InputError(t.where("alpha") + ": required key is missing");
      term.alpha = t.number("alpha", 0.0);
      t.finish();
      // Abaqus form 2 mu_i / alpha_i^2: each term adds mu_i to the shear modulus whatever the sign
      // of alpha_i, so mu_i > 0 is the per-term stability condition (mu_i alpha_i > 0 of the
      // classical form mu_i / alpha_i, rewritten).
      if (term.alpha == 0.0 || !(term.mu_Pa > 0.0))
        throw InputError(t.here() + "needs alpha != 0 and mu > 0 (a stable Ogden term in the Abaqus form)");
      m.ogden.push_back(term);
      m.mu_Pa += term.mu_Pa;
    }
    if (!(m.mu_Pa > 0)) throw InputError(map.where("terms") + ": the initial shear modulus sum(mu_i) must be positive");
    m.K_Pa = bulk_from(m.mu_Pa);
  }

  check_stiffness_range(map, m);
  if (!map.has("density"))
    throw InputError(map.where("density") + ": required key is missing (e.g. 1000 kg/m^3; gravity needs mass)");
  m.density_kg_m3 = quantity(map, "density", Dimension::Density, 0.0);
  if (!(m.density_kg_m3 >= 100.0 && m.density_kg_m3 <= 5000.0))
    throw InputError(map.where("density") + ": " + format_quantity(m.density_kg_m3, Dimension::Density) +
                     " is not a tissue density (soft tissue: 900-1100 kg/m^3); check the unit");
  m.source = map.text("source", "");
  map.finish();
  return m;
}

MaterialTable MaterialTable::from_yaml(YamlMap& map, const std::string& config_path) {
  MaterialTable table;
  table.source = map.source();
  if (map.has("preset")) {
    table.preset = map.text("preset", "");
    const fs::path p = resolve_preset(table.preset, config_path);
    YAML::Node root = load_yaml_file(p.string());
    YamlMap top(root, "", p.string());
    top.text("description", "");
    YamlMap inner = top.map("materials");
    if (inner.has("preset")) throw InputError(inner.where("preset") + ": a preset cannot load another preset");
    MaterialTable loaded = from_yaml(inner, p.string());
    top.finish();
    table.tissues = loaded.tissues;
    table.source += " (preset " + p.string() + ")";
  }
  for (const std::string& name : map.keys()) {
    if (name == "preset") continue;
    YamlMap entry = map.map(name);
    table.tissues[name] = parse_material(entry);
  }
  map.finish();
  return table;
}

MaterialTable MaterialTable::phantom_default() {
  // configs/materials/ucl-niftysim-invivo.yaml, which configs/phantom.yaml loads (tested equal).
  MaterialTable t;
  t.source = "<built-in phantom materials>";
  auto neo = [](double mu, const std::string& source) {
    MaterialSpec m;
    m.law = MaterialLaw::NeoHookean;
    m.mu_Pa = mu;
    m.C10_Pa = mu / 2;
    m.K_Pa = 50e3;
    m.density_kg_m3 = 1000.0;
    m.source = source;
    return m;
  };
  const std::string ucl = "UCL NiftySim prone-to-supine model builder (Han et al. 2012; Eiben et al. 2016)";
  t.tissues["fat"] = neo(150, ucl);
  t.tissues["fgt"] = neo(300, ucl);
  t.tissues["skin"] = neo(150, ucl);
  t.tissues["muscle"] = neo(600, ucl);
  t.tissues["tumor"] = neo(900, "assumed: 3 x fgt, the low end of the 3-6 fold stiffening of malignant tumours "
                                "(Samani et al. 2007, abstract)");
  return t;
}

void MaterialTable::to_yaml(YAML::Emitter& out) const {
  out << YAML::BeginMap;
  for (const auto& [name, m] : tissues) {
    out << YAML::Key << name << YAML::Value << YAML::Flow << YAML::BeginMap;
    out << YAML::Key << "law" << YAML::Value << material_law_name(m.law);
    switch (m.law) {
      case MaterialLaw::NeoHookean:
      case MaterialLaw::CompressibleNeoHookean:
        out << YAML::Key << "mu" << YAML::Value << format_quantity(m.mu_Pa, Dimension::Stress);
        break;
      case MaterialLaw::MooneyRivlin:
        out << YAML::Key << "C10" << YAML::Value << format_quantity(m.C10_Pa, Dimension::Stress);
        out << YAML::Key << "C01" << YAML::Value << format_quantity(m.C01_Pa, Dimension::Stress);
        break;
      case MaterialLaw::Ogden:
        out << YAML::Key << "terms" << YAML::Value << YAML::Flow << YAML::BeginSeq;
        for (const OgdenTerm& t : m.ogden)
          out << YAML::Flow << YAML::BeginMap << YAML::Key << "mu" << YAML::Value
              << format_quantity(t.mu_Pa, Dimension::Stress) << YAML::Key << "alpha" << YAML::Value << t.alpha
              << YAML::EndMap;
        out << YAML::EndSeq;
        break;
    }
    out << YAML::Key << "K" << YAML::Value << format_quantity(m.K_Pa, Dimension::Stress);
    out << YAML::Key << "density" << YAML::Value << format_quantity(m.density_kg_m3, Dimension::Density);
    if (!m.source.empty()) out << YAML::Key << "source" << YAML::Value << m.source;
    out << YAML::EndMap;
  }
  out << YAML::EndMap;
}

}  // namespace tissuemesh
