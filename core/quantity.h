// Physical quantities in config files: "<number> <unit>", e.g. "150 Pa", "0.3 kPa", "1000 kg/m^3",
// "9.81 m/s^2", "4e-5 1/Pa". Material parameters, densities and accelerations are read this way
// so that a kPa/Pa or kg/m^3 vs t/mm^3 confusion is impossible to make silently: a bare number or
// a unit of the wrong kind is an InputError naming the key and the accepted units.
#pragma once

#include "core/yaml_map.h"

#include <string>

namespace tissuemesh {

enum class Dimension { Stress, InverseStress, Density, Acceleration };

/// Accepted units, e.g. "Pa, kPa, MPa" (for messages and docs).
std::string accepted_units(Dimension dimension);

/// Parses "<number> <unit>" into SI (Pa, 1/Pa, kg/m^3, m/s^2). `where` names the key in errors.
double parse_quantity(const std::string& text, Dimension dimension, const std::string& where);

/// Optional key of `map` read as a quantity in SI, or `fallback` when absent.
double quantity(YamlMap& map, const std::string& key, Dimension dimension, double fallback);

/// "150 Pa", "1000 kg/m^3": SI value with its SI unit, shortest exact decimal form.
std::string format_quantity(double si_value, Dimension dimension);

}  // namespace tissuemesh
