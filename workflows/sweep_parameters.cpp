#include "workflows/sweep_parameters.h"

#include "core/errors.h"

#include <cmath>
#include <sstream>

namespace tissuemesh {

namespace {

struct Path {
  bool gravity = false;
  std::string tissue, constant;
};

const char* const kForms =
    "materials.<tissue>.<mu|K|E|nu|C10|C01|density> or model.gravity.acceleration";

Path split(const std::string& path) {
  Path p;
  if (path == "model.gravity.acceleration") {
    p.gravity = true;
    return p;
  }
  const auto first = path.find('.'), last = path.rfind('.');
  if (path.compare(0, first, "materials") != 0 || first == last || first == std::string::npos)
    throw InputError("sweep parameter '" + path + "': unknown path (" + kForms + ")");
  p.tissue = path.substr(first + 1, last - first - 1);
  p.constant = path.substr(last + 1);
  for (const char* c : {"mu", "K", "E", "nu", "C10", "C01", "density"})
    if (p.constant == c) return p;
  throw InputError("sweep parameter '" + path + "': unknown constant '" + p.constant + "' (" + kForms + ")");
}

std::string number(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

/// Scales the law's shear parameters so that its initial shear modulus becomes mu.
void set_mu(MaterialSpec& m, double mu) {
  const double f = mu / m.mu_Pa;
  m.mu_Pa = mu;
  m.C10_Pa *= f;
  m.C01_Pa *= f;
  for (OgdenTerm& t : m.ogden) t.mu_Pa *= f;
}

}  // namespace

bool parameter_dimension(const std::string& path, Dimension& dimension) {
  const Path p = split(path);
  if (p.gravity) {
    dimension = Dimension::Acceleration;
    return true;
  }
  if (p.constant == "nu") return false;
  dimension = p.constant == "density" ? Dimension::Density : Dimension::Stress;
  return true;
}

void check_parameter_path(const Model& model, const std::string& path) {
  const Path p = split(path);
  if (p.gravity) {
    if (!(model.gravity.acceleration_m_s2.norm() > 0.0))
      throw InputError("sweep parameter '" + path + "': the model has no gravity (model.gravity.direction none)");
    return;
  }
  std::string known;
  for (std::size_t t = 0; t < model.tissue_names.size(); ++t) {
    known += (t ? ", " : "") + model.tissue_names[t];
    if (model.tissue_names[t] != p.tissue) continue;
    const MaterialSpec& m = model.materials[t];
    if ((p.constant == "C10" || p.constant == "C01") && m.law != MaterialLaw::MooneyRivlin)
      throw InputError("sweep parameter '" + path + "': " + p.constant + " is a Mooney-Rivlin constant; tissue '" +
                       p.tissue + "' has another law (sweep mu instead)");
    return;
  }
  throw InputError("sweep parameter '" + path + "': the model has no tissue '" + p.tissue + "' (it has " + known + ")");
}

void apply_parameter(Model& model, const std::string& path, double value) {
  check_parameter_path(model, path);
  const Path p = split(path);
  const std::string what = "sweep parameter '" + path + "' = " + number(value);
  if (!std::isfinite(value)) throw InputError(what + ": not a finite value");
  if (p.gravity) {
    if (!(value >= 0.0 && value <= 100.0)) throw InputError(what + " m/s^2: outside [0, 100] m/s^2");
    model.gravity.acceleration_m_s2 = value * model.gravity.acceleration_m_s2.normalized();
    return;
  }
  std::size_t t = 0;
  while (model.tissue_names[t] != p.tissue) ++t;
  MaterialSpec& m = model.materials[t];
  const double E = m.young_modulus_Pa(), nu = m.poisson_ratio();
  if (p.constant == "density") {
    if (!(value >= 100.0 && value <= 5000.0)) throw InputError(what + " kg/m^3: outside [100, 5000] kg/m^3");
    m.density_kg_m3 = value;
    return;
  }
  if (p.constant == "nu") {
    if (!(value > -1.0 && value < 0.5))
      throw InputError(what + ": Poisson's ratio must lie in (-1, 0.5) (0.5 is incompressible: sweep K instead)");
    set_mu(m, E / (2.0 * (1.0 + value)));
    m.K_Pa = E / (3.0 * (1.0 - 2.0 * value));
    return;
  }
  if (!(value > 0.0)) throw InputError(what + " Pa: must be positive");
  if (p.constant == "mu") {
    set_mu(m, value);
  } else if (p.constant == "K") {
    m.K_Pa = value;
  } else if (p.constant == "E") {
    set_mu(m, value / (2.0 * (1.0 + nu)));
    m.K_Pa = value / (3.0 * (1.0 - 2.0 * nu));
  } else {  // C10 or C01 of a Mooney-Rivlin law
    (p.constant == "C10" ? m.C10_Pa : m.C01_Pa) = value;
    m.mu_Pa = 2.0 * (m.C10_Pa + m.C01_Pa);
  }
  if (!(m.poisson_ratio() < 0.5 && m.poisson_ratio() > -1.0))
    throw InputError(what + ": gives Poisson's ratio " + number(m.poisson_ratio()) + " outside (-1, 0.5)");
}

}  // namespace tissuemesh
