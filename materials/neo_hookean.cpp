// Compressible (coupled) neo-Hookean, ln J volumetric form (Bonet & Wood, "Nonlinear continuum
// mechanics for finite element analysis", 2nd ed., §6.4.3):
//   W = mu/2 (I1 - 3) - mu ln J + lambda/2 (ln J)^2
//   S = mu (I - C^-1) + lambda ln J C^-1
//   CC = lambda C^-1 (x) C^-1 + 2 (mu - lambda ln J) C^-1 (.) C^-1
#include "materials/hyperelastic_law.h"
#include "materials/tensor4.h"

#include <Eigen/LU>

#include <cmath>

namespace tissuemesh {

namespace {

class CompressibleNeoHookean : public HyperelasticLaw {
 public:
  CompressibleNeoHookean(double mu, double lambda) : mu_(mu), lambda_(lambda) {}
  std::string name() const override { return "compressible neo-Hookean (ln J)"; }
  double energy(const Eigen::Matrix3d& C) const override {
    const double lnJ = 0.5 * std::log(C.determinant());
    return 0.5 * mu_ * (C.trace() - 3.0) - mu_ * lnJ + 0.5 * lambda_ * lnJ * lnJ;
  }
  Eigen::Matrix3d pk2(const Eigen::Matrix3d& C) const override {
    const Eigen::Matrix3d Ci = C.inverse();
    const double lnJ = 0.5 * std::log(C.determinant());
    return mu_ * (Eigen::Matrix3d::Identity() - Ci) + lambda_ * lnJ * Ci;
  }
  Tangent6 tangent(const Eigen::Matrix3d& C) const override {
    const Eigen::Matrix3d Ci = C.inverse();
    const double lnJ = 0.5 * std::log(C.determinant());
    return lambda_ * tensor4::outer(Ci, Ci) + 2.0 * (mu_ - lambda_ * lnJ) * tensor4::sym_product(Ci);
  }
  Volumetric volumetric(double J) const override {
    const double lnJ = std::log(J);
    return {0.5 * lambda_ * lnJ * lnJ, lambda_ * lnJ / J, lambda_ * (1.0 - lnJ) / (J * J)};
  }

 private:
  double mu_, lambda_;
};

}  // namespace

std::unique_ptr<HyperelasticLaw> make_compressible_neo_hookean(double mu, double lambda) {
  return std::make_unique<CompressibleNeoHookean>(mu, lambda);
}

}  // namespace tissuemesh
