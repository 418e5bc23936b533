// make_law: MaterialSpec (SI) -> HyperelasticLaw in the requested unit system. Only stresses carry
// a unit (moduli, C10, C01, mu_i); Ogden exponents are dimensionless and pass through unchanged.
#include "materials/make_law.h"

#include <stdexcept>
#include <vector>

namespace tissuemesh {

std::unique_ptr<HyperelasticLaw> make_law(const MaterialSpec& spec, UnitSystem units) {
  const auto stress = [units](double pascal) { return stress_from_pascal(units, pascal); };
  switch (spec.law) {
    case MaterialLaw::NeoHookean:
      // The uncoupled neo-Hookean is Mooney-Rivlin with C01 = 0 (the same energy, not a look-alike).
      return make_uncoupled_mooney_rivlin(stress(spec.C10_Pa), 0.0, stress(spec.K_Pa));
    case MaterialLaw::CompressibleNeoHookean:
      return make_compressible_neo_hookean(stress(spec.mu_Pa), stress(spec.lambda_Pa()));
    case MaterialLaw::MooneyRivlin:
      return make_uncoupled_mooney_rivlin(stress(spec.C10_Pa), stress(spec.C01_Pa), stress(spec.K_Pa));
    case MaterialLaw::Ogden: {
      std::vector<double> mu, alpha;
      for (const OgdenTerm& t : spec.ogden) {
        mu.push_back(stress(t.mu_Pa));
        alpha.push_back(t.alpha);
      }
      return make_uncoupled_ogden(mu, alpha, stress(spec.K_Pa));
    }
  }
  // Only reachable with an out-of-range enum value: a programming error, not bad input.
  throw std::logic_error("make_law: unknown MaterialLaw " + std::to_string(static_cast<int>(spec.law)));
}

}  // namespace tissuemesh
