#include "core/material_spec.h"

#include <stdexcept>

namespace tissuemesh {

std::string material_law_name(MaterialLaw law) {
  switch (law) {
    case MaterialLaw::NeoHookean:
      return "neo-hookean";
    case MaterialLaw::CompressibleNeoHookean:
      return "compressible-neo-hookean";
    case MaterialLaw::MooneyRivlin:
      return "mooney-rivlin";
    case MaterialLaw::Ogden:
      return "ogden";
  }
  // Only reachable with an out-of-range enum value: a programming error, not bad input.
  throw std::logic_error("material_law_name: unknown MaterialLaw " + std::to_string(static_cast<int>(law)));
}

}  // namespace tissuemesh
