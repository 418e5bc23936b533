#include "core/unit_system.h"

#include "core/errors.h"

namespace tissuemesh {

namespace {
// How many SI units make one unit of the system (docs/formats.md, "Conventions shared by every
// file"; accelerations: system units per m/s^2). Conversions divide (multiply for accelerations)
// by exactly representable powers of ten, so that typed values convert to the nearest double
// (50 kPa -> 0.05 MPa exactly, not 0.049999999999999996 as multiplying by 1e-6 gives) and
// millimetre coordinates pass through the mm systems unchanged.
struct Scales {
  const char* name;
  double pa_per_stress, kg_m3_per_density, acceleration_per_m_s2, mm_per_length, force_per_newton;
  const char *stress_unit, *density_unit, *acceleration_unit, *length_unit, *force_unit;
};
const Scales& scales(UnitSystem s) {
  static const Scales si{"SI", 1.0, 1.0, 1.0, 1e3, 1.0, "Pa", "kg/m^3", "m/s^2", "m", "N"};
  static const Scales mm_t_s{"mm-t-s", 1e6, 1e12, 1e3, 1.0, 1.0, "MPa", "t/mm^3", "mm/s^2", "mm", "N"};
  static const Scales mm_kg_s{"mm-kg-s", 1e3, 1e9, 1e3, 1.0, 1e3, "kPa", "kg/mm^3", "mm/s^2", "mm", "mN"};
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
std::string force_unit(UnitSystem s) { return scales(s).force_unit; }

double stress_from_pascal(UnitSystem s, double pascal) { return pascal / scales(s).pa_per_stress; }
double density_from_kg_per_m3(UnitSystem s, double rho) { return rho / scales(s).kg_m3_per_density; }
double acceleration_from_m_per_s2(UnitSystem s, double a) { return a * scales(s).acceleration_per_m_s2; }
double length_from_mm(UnitSystem s, double mm) { return mm / scales(s).mm_per_length; }
double force_from_newton(UnitSystem s, double newton) { return newton * scales(s).force_per_newton; }

}  // namespace tissuemesh
