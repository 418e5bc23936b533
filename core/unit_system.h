// Consistent unit systems for exported models (no FE solver knows units: docs/formats.md,
// "Conventions shared by every file").
//
// The toolkit works internally in millimetres (geometry) and takes material and load inputs in SI
// (Pa, kg/m^3, m/s^2); a UnitSystem converts them consistently for a model file:
//   SI       m,  kg, s -> N,  Pa;  water 1000 kg/m^3; g 9.81 m/s^2
//   mm-t-s   mm, t,  s -> N,  MPa; water 1e-9 t/mm^3; g 9810 mm/s^2   (Abaqus/CalculiX "mm-N-s")
//   mm-kg-s  mm, kg, s -> mN, kPa; water 1e-6 kg/mm^3; g 9810 mm/s^2
// Consistency check used by the tests: density * gravity must equal the weight per volume
// (9810 Pa/m for water) expressed in the system's stress per length.
#pragma once

#include <string>

namespace tissuemesh {

enum class UnitSystem { SI, MillimetreTonneSecond, MillimetreKilogramSecond };

/// "SI", "mm-t-s", "mm-kg-s".
std::string unit_system_name(UnitSystem system);
/// Inverse of unit_system_name; throws InputError naming `text` and listing the known names.
UnitSystem parse_unit_system(const std::string& text);

/// Unit names for reports and file comments, e.g. "MPa", "t/mm^3", "mm/s^2", "mm".
std::string stress_unit(UnitSystem system);
std::string density_unit(UnitSystem system);
std::string acceleration_unit(UnitSystem system);
std::string length_unit(UnitSystem system);
/// Force unit = stress x length^2: "N" (SI, mm-t-s) or "mN" (mm-kg-s).
std::string force_unit(UnitSystem system);

/// Conversions of SI input values (and of millimetre geometry) into the system's units.
double stress_from_pascal(UnitSystem system, double pascal);
double density_from_kg_per_m3(UnitSystem system, double kg_per_m3);
double acceleration_from_m_per_s2(UnitSystem system, double m_per_s2);
double length_from_mm(UnitSystem system, double mm);
/// Newtons into the system's force unit (x 1, or x 1000 for mN); divide by it to get newtons.
double force_from_newton(UnitSystem system, double newton);

}  // namespace tissuemesh
