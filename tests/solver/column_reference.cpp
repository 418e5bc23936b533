#include "solver/column_reference.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace tissuemesh::test {

namespace {

// Bisection of an increasing f on [lo, hi] with f(lo) <= 0 <= f(hi), down to adjacent doubles.
template <class F>
double bisect(F f, double lo, double hi) {
  for (int it = 0; it < 2000; ++it) {
    const double mid = 0.5 * (lo + hi);
    if (mid <= lo || mid >= hi) break;
    (f(mid) < 0.0 ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

// Brackets the root of an increasing f around 1 by doubling the distance (stretches > 0).
template <class F>
double increasing_root(F f) {
  double lo = 1.0, hi = 1.0;
  if (f(1.0) < 0.0) {
    hi = 2.0;
    while (f(hi) < 0.0) hi *= 2.0;
  } else {
    lo = 0.5;
    while (f(lo) > 0.0) lo *= 0.5;
  }
  return bisect(f, lo, hi);
}

}  // namespace

std::vector<std::pair<double, double>> gauss_legendre_01(int n) {
  if (n < 1) throw std::invalid_argument("gauss_legendre_01: n must be >= 1");
  // Newton on the Legendre polynomial P_n from the Chebyshev-like initial guesses (Numerical Recipes
  // gauleg), then mapped from [-1, 1] to [0, 1].
  std::vector<std::pair<double, double>> rule(n);
  const double pi = std::acos(-1.0);
  for (int i = 0; i < n; ++i) {
    double x = std::cos(pi * (i + 0.75) / (n + 0.5)), dp = 0.0;
    for (int it = 0; it < 100; ++it) {
      double p0 = 1.0, p1 = 0.0;
      for (int j = 1; j <= n; ++j) {
        const double p2 = p1;
        p1 = p0;
        p0 = ((2.0 * j - 1.0) * x * p1 - (j - 1.0) * p2) / j;
      }
      dp = n * (x * p0 - p1) / (x * x - 1.0);
      const double dx = p0 / dp;
      x -= dx;
      if (std::abs(dx) < 1e-16) break;
    }
    rule[i] = {0.5 * (1.0 - x), 1.0 / ((1.0 - x * x) * dp * dp)};
  }
  return rule;
}

double principal_pk1(MaterialLaw law, double mu, double K, double l1, double l2, double l3) {
  const double J = l1 * l2 * l3;
  switch (law) {
    case MaterialLaw::CompressibleNeoHookean: {
      const double lambda_L = K - 2.0 * mu / 3.0;
      return mu * (l1 - 1.0 / l1) + lambda_L * std::log(J) / l1;
    }
    case MaterialLaw::NeoHookean: {
      const double I1 = l1 * l1 + l2 * l2 + l3 * l3;
      return mu * std::pow(J, -2.0 / 3.0) * (l1 - I1 / (3.0 * l1)) + K * (J - 1.0) * J / l1;
    }
    default:
      throw std::invalid_argument("principal_pk1: only the two neo-Hookean laws have a reference here");
  }
}

UniaxialState uniaxial_stress(MaterialLaw law, double mu, double K, double lambda) {
  UniaxialState st;
  st.lateral_stretch = increasing_root([&](double b) { return principal_pk1(law, mu, K, b, b, lambda); });
  const double b = st.lateral_stretch;
  st.P11 = principal_pk1(law, mu, K, lambda, b, b);
  st.J = lambda * b * b;
  return st;
}

ConfinedColumn::ConfinedColumn(MaterialLaw law, double mu, double K, double rho_g, double length, int sign, int panels)
    : law_(law), mu_(mu), K_(K), rho_g_(rho_g), length_(length), sign_(sign) {
  if (panels < 1 || (sign != 1 && sign != -1)) throw std::invalid_argument("ConfinedColumn: bad panels or sign");
  const auto rule = gauss_legendre_01(8);
  const double h = length / panels;
  table_.assign(panels + 1, 0.0);
  slope_.assign(panels + 1, 0.0);
  for (int k = 0; k <= panels; ++k) slope_[k] = stretch(k * h) - 1.0;
  for (int k = 0; k < panels; ++k) {
    double sum = 0.0;
    for (const auto& [x, w] : rule) sum += w * (stretch((k + x) * h) - 1.0);
    table_[k + 1] = table_[k] + h * sum;
  }
}

double ConfinedColumn::axial_stress(double a) const { return principal_pk1(law_, mu_, K_, a, 1.0, 1.0); }

double ConfinedColumn::stretch(double s) const {
  const double target = sign_ * rho_g_ * s;
  return increasing_root([&](double a) { return axial_stress(a) - target; });
}

double ConfinedColumn::extension(double s) const {
  const int panels = static_cast<int>(table_.size()) - 1;
  const double h = length_ / panels;
  const int k = std::clamp(static_cast<int>(s / h), 0, panels - 1);
  const double t = (s - k * h) / h;
  const double m0 = slope_[k], m1 = slope_[k + 1];
  // Cubic Hermite basis on [0, 1].
  const double h00 = (1 + 2 * t) * (1 - t) * (1 - t), h10 = t * (1 - t) * (1 - t);
  const double h01 = t * t * (3 - 2 * t), h11 = t * t * (t - 1);
  return h00 * table_[k] + h10 * h * m0 + h01 * table_[k + 1] + h11 * h * m1;
}

}  // namespace tissuemesh::test
