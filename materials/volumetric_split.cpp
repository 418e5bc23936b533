#include "materials/volumetric_split.h"

#include "materials/tensor4.h"

#include <Eigen/LU>

#include <cmath>

namespace tissuemesh {

namespace {

class ShearPart : public HyperelasticLaw {
 public:
  explicit ShearPart(const HyperelasticLaw& full) : full_(full) {}
  std::string name() const override { return full_.name() + " without U(J)"; }
  double energy(const Eigen::Matrix3d& C) const override { return evaluate(C, nullptr, nullptr); }
  Eigen::Matrix3d pk2(const Eigen::Matrix3d& C) const override {
    Eigen::Matrix3d S;
    evaluate(C, &S, nullptr);
    return S;
  }
  Tangent6 tangent(const Eigen::Matrix3d& C) const override {
    Tangent6 CC;
    evaluate(C, nullptr, &CC);
    return CC;
  }
  // W - U, S - J U' C^-1 and CC - J (U' + J U'') C^-1 (x) C^-1 + 2 J U' C^-1 (.) C^-1, from the
  // full law's (the three calls above give the same values through this one).
  double evaluate(const Eigen::Matrix3d& C, Eigen::Matrix3d* S, Tangent6* CC) const override {
    const double W = full_.evaluate(C, S, CC);
    const double J = std::sqrt(C.determinant());
    const Volumetric v = full_.volumetric(J);
    if (S || CC) {
      const Eigen::Matrix3d Ci = C.inverse();
      if (S) *S -= J * v.dU * Ci;
      if (CC) {
        *CC -= J * (v.dU + J * v.d2U) * tensor4::outer(Ci, Ci);
        *CC += 2.0 * J * v.dU * tensor4::sym_product(Ci);
      }
    }
    return W - v.U;
  }
  Volumetric volumetric(double) const override { return {}; }

 private:
  const HyperelasticLaw& full_;
};

}  // namespace

std::unique_ptr<HyperelasticLaw> make_shear_part(const HyperelasticLaw& full) {
  return std::make_unique<ShearPart>(full);
}

}  // namespace tissuemesh
