#include "core/quantity.h"

#include "core/errors.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <utility>
#include <vector>

namespace tissuemesh {

namespace {

using UnitList = std::vector<std::pair<const char*, double>>;  // unit -> factor to SI

const UnitList& units_of(Dimension d) {
  static const UnitList stress{{"Pa", 1.0}, {"kPa", 1e3}, {"MPa", 1e6}, {"N/mm^2", 1e6}};
  static const UnitList inverse{{"1/Pa", 1.0}, {"1/kPa", 1e-3}, {"1/MPa", 1e-6}};
  static const UnitList density{{"kg/m^3", 1.0}, {"g/cm^3", 1e3}, {"g/mL", 1e3}, {"kg/mm^3", 1e9},
                                {"t/mm^3", 1e12}};
  static const UnitList accel{{"m/s^2", 1.0}, {"mm/s^2", 1e-3}};
  switch (d) {
    case Dimension::Stress: return stress;
    case Dimension::InverseStress: return inverse;
    case Dimension::Density: return density;
    case Dimension::Acceleration: return accel;
  }
  return stress;
}

const char* si_unit(Dimension d) { return units_of(d).front().first; }

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t");
  if (b == std::string::npos) return "";
  return s.substr(b, s.find_last_not_of(" \t") - b + 1);
}

}  // namespace

std::string accepted_units(Dimension dimension) {
  std::string out;
  for (const auto& [unit, factor] : units_of(dimension)) out += (out.empty() ? "" : ", ") + std::string(unit);
  return out;
}

double parse_quantity(const std::string& text, Dimension dimension, const std::string& where) {
  const std::string hint = " (write a number and a unit, e.g. '1.5 " + std::string(si_unit(dimension)) +
                           "'; units: " + accepted_units(dimension) + ")";
  const std::string t = trim(text);
  const char* begin = t.c_str();
  char* end = nullptr;
  const double value = std::strtod(begin, &end);
  if (end == begin || !std::isfinite(value))
    throw InputError(where + ": '" + text + "' is not a quantity" + hint);
  const std::string unit = trim(std::string(end));
  if (unit.empty()) throw InputError(where + ": '" + text + "' has no unit" + hint);
  for (const auto& [name, factor] : units_of(dimension))
    if (unit == name) return value * factor;
  for (Dimension other : {Dimension::Stress, Dimension::InverseStress, Dimension::Density, Dimension::Acceleration})
    for (const auto& [name, factor] : units_of(other))
      if (unit == name)
        throw InputError(where + ": '" + text + "': unit '" + unit + "' is the wrong kind of unit here" + hint);
  throw InputError(where + ": '" + text + "': unknown unit '" + unit + "'" + hint);
}

double quantity(YamlMap& map, const std::string& key, Dimension dimension, double fallback) {
  if (!map.has(key)) return fallback;
  return parse_quantity(map.text(key, ""), dimension, map.where(key));
}

std::string format_quantity(double si_value, Dimension dimension) {
  // 15 significant digits print typed values as typed (150, 9.81, 1e-06); 17 when that does not
  // read back to the same double, so that printed configs re-load exactly.
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.15g", si_value);
  if (std::strtod(buf, nullptr) != si_value) std::snprintf(buf, sizeof buf, "%.17g", si_value);
  return std::string(buf) + " " + si_unit(dimension);
}

}  // namespace tissuemesh
