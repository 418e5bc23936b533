#include "materials/elastic_constants.h"

#include "core/errors.h"

#include <cmath>
#include <sstream>

namespace tissuemesh {

namespace {
std::string show(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}
}  // namespace

ElasticConstants::ElasticConstants(double mu, double K, const std::string& given) : mu_(mu), K_(K) {
  if (!std::isfinite(mu) || !(mu > 0.0))
    throw InputError(given + ": shear modulus mu = " + show(mu) + " must be positive (a solid resists shear)");
  if (!std::isfinite(K) || !(K > 0.0))
    throw InputError(given + ": bulk modulus K = " + show(K) +
                     " must be positive (a solid resists compression; K <= 0 means nu <= -1)");
}

ElasticConstants ElasticConstants::from_young_poisson(double E, double nu) {
  const std::string given = "E = " + show(E) + ", nu = " + show(nu);
  if (!std::isfinite(E) || !(E > 0.0)) throw InputError(given + ": Young's modulus must be positive");
  if (!std::isfinite(nu) || nu >= 0.5)
    throw InputError(given + ": Poisson's ratio must be below 0.5 (nu = 0.5 is incompressible: no finite "
                             "bulk modulus); for nearly incompressible tissue give mu and a bulk modulus K >> mu");
  if (nu <= -1.0) throw InputError(given + ": Poisson's ratio must be above -1");
  return ElasticConstants(E / (2.0 * (1.0 + nu)), E / (3.0 * (1.0 - 2.0 * nu)), given);
}

ElasticConstants ElasticConstants::from_shear_bulk(double mu, double K) {
  return ElasticConstants(mu, K, "mu = " + show(mu) + ", K = " + show(K));
}

ElasticConstants ElasticConstants::from_lame(double mu, double lambda) {
  return ElasticConstants(mu, lambda + 2.0 * mu / 3.0, "mu = " + show(mu) + ", lambda = " + show(lambda));
}

ElasticConstants ElasticConstants::from_neo_hooke(double C10, double D1) {
  const std::string given = "C10 = " + show(C10) + ", D1 = " + show(D1);
  if (!std::isfinite(D1) || !(D1 > 0.0))
    throw InputError(given + ": D1 must be positive (D1 = 2/K; CalculiX silently replaces D1 = 0 by a default)");
  return ElasticConstants(2.0 * C10, 2.0 / D1, given);
}

ElasticConstants ElasticConstants::from_mooney_rivlin(double c1, double c2, double k) {
  return ElasticConstants(2.0 * (c1 + c2), k, "c1 = " + show(c1) + ", c2 = " + show(c2) + ", k = " + show(k));
}

}  // namespace tissuemesh
