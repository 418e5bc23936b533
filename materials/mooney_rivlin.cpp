// Uncoupled Mooney-Rivlin with the Abaqus volumetric term (uncoupled neo-Hookean when C01 = 0):
//   W = C10 (I1bar - 3) + C01 (I2bar - 3) + K/2 (J - 1)^2,  I1bar = J^-2/3 I1, I2bar = J^-4/3 I2.
// With dJ/dC = J/2 C^-1, dC^-1/dC = -C^-1 (.) C^-1, dI2/dC = I1 I - C:
//   S = 2 C10 J^-2/3 (I - I1/3 C^-1) + 2 C01 J^-4/3 (I1 I - C - 2/3 I2 C^-1) + K J (J - 1) C^-1
//   CC = 2 dS/dC, term by term below (checked against finite differences in the tests).
#include "materials/hyperelastic_law.h"
#include "materials/tensor4.h"

#include <Eigen/LU>

#include <cmath>

namespace tissuemesh {

namespace {

class UncoupledMooneyRivlin : public HyperelasticLaw {
 public:
  UncoupledMooneyRivlin(double C10, double C01, double K) : c10_(C10), c01_(C01), k_(K) {}
  std::string name() const override {
    return c01_ == 0.0 ? "uncoupled neo-Hookean ((J-1)^2)" : "uncoupled Mooney-Rivlin ((J-1)^2)";
  }
  double energy(const Eigen::Matrix3d& C) const override { return energy(Invariants(C)); }
  Eigen::Matrix3d pk2(const Eigen::Matrix3d& C) const override { return pk2(C, Invariants(C)); }
  Tangent6 tangent(const Eigen::Matrix3d& C) const override { return tangent(C, Invariants(C)); }
  double evaluate(const Eigen::Matrix3d& C, Eigen::Matrix3d* S, Tangent6* CC) const override {
    const Invariants v(C);
    if (S) *S = pk2(C, v);
    if (CC) *CC = tangent(C, v);
    return energy(v);
  }
  Volumetric volumetric(double J) const override {
    return {0.5 * k_ * (J - 1.0) * (J - 1.0), k_ * (J - 1.0), k_};
  }

 private:
  struct Invariants {
    explicit Invariants(const Eigen::Matrix3d& C)
        : Ci(C.inverse()), I1(C.trace()), I2(0.5 * (I1 * I1 - (C * C).trace())), J(std::sqrt(C.determinant())),
          j23(std::pow(J, -2.0 / 3.0)), j43(j23 * j23) {}
    Eigen::Matrix3d Ci;
    double I1, I2, J, j23, j43;
  };
  double energy(const Invariants& v) const {
    return c10_ * (v.j23 * v.I1 - 3.0) + c01_ * (v.j43 * v.I2 - 3.0) + 0.5 * k_ * (v.J - 1.0) * (v.J - 1.0);
  }
  Eigen::Matrix3d pk2(const Eigen::Matrix3d& C, const Invariants& v) const {
    const Eigen::Matrix3d I = Eigen::Matrix3d::Identity();
    Eigen::Matrix3d S = 2.0 * c10_ * v.j23 * (I - v.I1 / 3.0 * v.Ci) + k_ * v.J * (v.J - 1.0) * v.Ci;
    if (c01_ != 0.0) S += 2.0 * c01_ * v.j43 * (v.I1 * I - C - 2.0 / 3.0 * v.I2 * v.Ci);
    return S;
  }
  Tangent6 tangent(const Eigen::Matrix3d& C, const Invariants& v) const {
    using tensor4::outer;
    using tensor4::sym_product;
    const Eigen::Matrix3d I = Eigen::Matrix3d::Identity();
    const Tangent6 CiCi = outer(v.Ci, v.Ci), Ci_sym = sym_product(v.Ci);
    // 2 d/dC of 2 C10 J^-2/3 (I - I1/3 C^-1)
    const Tangent6 t1 = 4.0 * c10_ * v.j23 *
                        (-1.0 / 3.0 * outer(I, v.Ci) - 1.0 / 3.0 * outer(v.Ci, I) + v.I1 / 9.0 * CiCi +
                         v.I1 / 3.0 * Ci_sym);
    // 2 d/dC of K (J^2 - J) C^-1
    const Tangent6 t3 = k_ * ((2.0 * v.J - 1.0) * v.J * CiCi - 2.0 * (v.J * v.J - v.J) * Ci_sym);
    if (c01_ == 0.0) return t1 + t3;  // neo-Hookean: the C01 term is zero (the assembly's hot path)
    // 2 d/dC of 2 C01 J^-4/3 (I1 I - C - 2/3 I2 C^-1)
    const Eigen::Matrix3d B = v.I1 * I - C - 2.0 / 3.0 * v.I2 * v.Ci;
    const Tangent6 t2 = 4.0 * c01_ * v.j43 *
                        (-2.0 / 3.0 * outer(B, v.Ci) + outer(I, I) - sym_product(I) -
                         2.0 / 3.0 * outer(v.Ci, v.I1 * I - C) + 2.0 / 3.0 * v.I2 * Ci_sym);
    return t1 + t2 + t3;
  }
  double c10_, c01_, k_;
};

}  // namespace

std::unique_ptr<HyperelasticLaw> make_uncoupled_mooney_rivlin(double C10, double C01, double K) {
  return std::make_unique<UncoupledMooneyRivlin>(C10, C01, K);
}

}  // namespace tissuemesh
