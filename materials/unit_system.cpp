#include "materials/unit_system.h"

#include "core/errors.h"

namespace tissuemesh {

namespace {
// Scale factors from SI (stress, density, acceleration, length from metres), formats.md §4.
struct Scales {
  const char* name;
  double stress, density, acceleration, length_per_m;
  const char *stress_unit, *density_unit, *acceleration_unit, *length_unit;
};
const Scales& scales(UnitSystem s) {
  static const Scales si{"SI", 1.0, 1.0, 1.0, 1.0, "Pa", "kg/m^3", "m/s^2", "m"};
  static const Scales mm_t_s{"mm-t-s", 1e-6, 1e-12, 1e3, 1e3, "MPa", "t/mm^3", "mm/s^2", "mm"};
  static const Scales mm_kg_s{"mm-kg-s", 1e-3, 1e-9, 1e3, 1e3, "kPa", "kg/mm^3", "mm/s^2", "mm"};
  switch (s) {
    case UnitSystem::SI:
      return si;
    case UnitSystem::MillimetreTonneSecond:
      return mm_t_s;
    case UnitSystem::MillimetreKilogramSecond:
      return mm_kg_s;
  }
  return si;
}
}  // namespace

std::string unit_system_name(UnitSystem system) { return scales(system).name; }

UnitSystem parse_unit_system(const std::string& text) {
  for (UnitSystem s : {UnitSystem::SI, UnitSystem::MillimetreTonneSecond, UnitSystem::MillimetreKilogramSecond})
    if (text == scales(s).name) return s;
  throw InputError("unknown unit system '" + text + "' (known: SI, mm-t-s, mm-kg-s)");
}

std::string stress_unit(UnitSystem s) { return scales(s).stress_unit; }
std::string density_unit(UnitSystem s) { return scales(s).density_unit; }
std::string acceleration_unit(UnitSystem s) { return scales(s).acceleration_unit; }
std::string length_unit(UnitSystem s) { return scales(s).length_unit; }

double stress_from_pascal(UnitSystem s, double pascal) { return pascal * scales(s).stress; }
double density_from_kg_per_m3(UnitSystem s, double rho) { return rho * scales(s).density; }
double acceleration_from_m_per_s2(UnitSystem s, double a) { return a * scales(s).acceleration; }
double length_from_mm(UnitSystem s, double mm) { return mm * 1e-3 * scales(s).length_per_m; }

}  // namespace tissuemesh
