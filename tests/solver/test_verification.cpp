// Solver-level verification of the built-in static solver against exact solutions
// (docs/verification.md, "Solver: analytic references"):
//   1. the finite-strain confined column: exact 3D solution F = diag(1, 1, a(Z)) for both
//      volumetric forms, hanging and standing; tet4 and tet10 converge to it at their rates;
//   2. the small-strain hanging bar (Timoshenko & Goodier, "Theory of Elasticity"): exact 3D linear
//      solution with Poisson contraction; tet4 converges at O(h^2), tet10 reproduces the quadratic
//      field exactly;
//   3. reactions balance the weight (or each other) to kSolverEquilibriumRel in every solve;
//   4. homogeneous uniaxial stress at structure level (the uniaxial table): axial reaction / area =
//      P11 and the lateral stretch of the free faces.
// The 1-D references come from tests/solver/column_reference.h, checked first against the tables.
// Measured errors and rates are printed on "[ verify   ]" lines.
#include "solver_check/static_solver.h"
#include "solver_check/tet_shape.h"

#include "core/model_builder.h"
#include "solver/column_reference.h"
#include "support/model_fixture.h"
#include "support/tolerances.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

namespace tissuemesh {
namespace {

using Eigen::Vector3d;
using test::ConfinedColumn;

// Parameters of the confined-column and uniaxial tables (SI).
constexpr double kMu = 1000.0;   // Pa
constexpr double kRho = 1000.0;  // kg/m^3
constexpr double kG = 9.81;      // m/s^2
constexpr double kRhoG = kRho * kG;

double bulk_modulus(double nu) { return 2.0 * kMu * (1.0 + nu) / (3.0 * (1.0 - 2.0 * nu)); }

MaterialSpec neo_hookean(MaterialLaw law, double nu) {
  MaterialSpec m;
  m.law = law;
  m.mu_Pa = kMu;
  m.C10_Pa = law == MaterialLaw::NeoHookean ? kMu / 2.0 : 0.0;
  m.K_Pa = bulk_modulus(nu);
  m.density_kg_m3 = kRho;
  m.source = "docs/verification.md, analytic references";
  return m;
}

const char* law_tag(MaterialLaw law) { return law == MaterialLaw::NeoHookean ? "J1sq" : "lnJ"; }
const char* order_tag(ElementOrder order) { return order == ElementOrder::Linear ? "tet4" : "tet10"; }

/// A node set on the plane through `point` with `normal` (grid nodes lie on it exactly).
NodeSetSettings plane_set(const std::string& name, const Vector3d& point, const Vector3d& normal, Constraint c) {
  NodeSetSettings s;
  s.name = name;
  s.selection = test::grid_plane(point, normal);
  s.constraint = c;
  return s;
}

ModelSettings settings(ElementOrder order, const Vector3d& gravity_direction) {
  ModelSettings s;
  s.units = UnitSystem::MillimetreTonneSecond;  // mm, N, MPa
  s.element = order;
  if (gravity_direction.norm() > 0) {
    s.gravity.direction = "vector";
    s.gravity.vector = gravity_direction.normalized();
    s.gravity.m_s2 = kG;
  } else {
    s.gravity.direction = "none";
  }
  // Tight enough that the solver's error stays far below every discretisation error measured here.
  s.analysis.residual_tolerance = test::kSolverTightResidualRel;
  return s;
}

Model build(const TetMesh& mesh, const ModelSettings& s, const MaterialSpec& spec) {
  return build_model(mesh, s, {{"tissue", spec}}, "verification");
}

// ---- measuring ---------------------------------------------------------------------------------

/// Conical (collapsed Gauss-Legendre 4 x 4 x 4) rule on the reference tetrahedron: exact for
/// polynomials of total degree <= 5, so |u_h - u|^2 with both quadratic (tet10) is integrated
/// exactly; weights sum to 1/6.
const QuadratureRule& error_rule() {
  static const QuadratureRule rule = [] {
    QuadratureRule q;
    const auto gl = test::gauss_legendre_01(4);
    for (const auto& [u, wu] : gl)
      for (const auto& [v, wv] : gl)
        for (const auto& [w, ww] : gl)
          q.push_back({Vector3d(u, v * (1 - u), w * (1 - u) * (1 - v)), wu * wv * ww * (1 - u) * (1 - u) * (1 - v)});
    return q;
  }();
  return rule;
}

struct L2Error {
  double error = 0.0;  ///< ||u_h - u|| over the volume (mm * mm^1.5)
  double norm = 0.0;   ///< ||u||
  double relative() const { return error / norm; }
};

/// L2 norm over the reference volume of u_h (nodal values, interpolated with the element's own
/// shape functions) minus exact(X), X in mm, both in mm.
L2Error l2_error(const Model& model, const std::vector<Vector3d>& u,
                 const std::function<Vector3d(const Vector3d&)>& exact) {
  const int n = model.nodes_per_element();
  double e2 = 0.0, u2 = 0.0;
  for (const auto& el : model.elements) {
    const Vector3d &X0 = model.nodes[el[0]], &X1 = model.nodes[el[1]], &X2 = model.nodes[el[2]],
                   &X3 = model.nodes[el[3]];
    const double detJ = (X1 - X0).dot((X2 - X0).cross(X3 - X0));  // straight elements: constant
    for (const QuadraturePoint& q : error_rule()) {
      const ShapeValues N = tet_shape_values(model.order, q.xi);
      Vector3d X = Vector3d::Zero(), uh = Vector3d::Zero();
      for (int a = 0; a < n; ++a) {
        X += N[a] * model.nodes[el[a]];
        uh += N[a] * u[el[a]];
      }
      const Vector3d ue = exact(X);
      e2 += q.weight * detJ * (uh - ue).squaredNorm();
      u2 += q.weight * detJ * ue.squaredNorm();
    }
  }
  return {std::sqrt(e2), std::sqrt(u2)};
}

/// log2 of successive error ratios (meshes refined by 2).
std::vector<double> rates(const std::vector<double>& e) {
  std::vector<double> r;
  for (std::size_t i = 1; i < e.size(); ++i) r.push_back(std::log2(e[i - 1] / e[i]));
  return r;
}

std::string join(const std::vector<double>& v, int precision = 3) {
  std::ostringstream s;
  s << std::setprecision(precision);
  for (std::size_t i = 0; i < v.size(); ++i) s << (i ? ", " : "") << v[i];
  return s.str();
}

/// |sum of the reactions + total load| / scale, from the per-node list (and the total checked
/// against it).
double reaction_imbalance(const SolveResult& r, double scale) {
  Vector3d sum = Vector3d::Zero();
  for (const NodeReaction& f : r.reactions) sum += f.force;
  EXPECT_LE((sum - r.total_reaction).norm(), test::kRelativeRoundoff * scale);
  return (sum + r.total_load).norm() / scale;
}

/// One assembly thread: the suite runs on shared machines where OpenMP threads would only wait for
/// each other (results are bit-for-bit the same for any thread count, static_solver.h).
SolveOptions single_thread() {
  SolveOptions o;
  o.threads = 1;
  return o;
}

bool near(double a, double b) { return std::abs(a - b) <= 1e-9; }

// ---- the 1-D references against the tabulated values -------------------------------------------

struct ColumnRow {
  double nu;
  MaterialLaw law;
  double hanging_mm, standing_mm;
};

TEST(VerificationColumnReference, ReproducesTheConfinedColumnTable) {
  // Confined-column tip displacements (mm, 4 decimals): L = 0.1 m, rho = 1000 kg/m^3, g = 9.81,
  // mu = 1000 Pa.
  const MaterialLaw lnJ = MaterialLaw::CompressibleNeoHookean, J1 = MaterialLaw::NeoHookean;
  const ColumnRow rows[] = {{0.30, lnJ, 16.8201, -11.9122}, {0.30, J1, 15.0928, -12.7954},
                            {0.45, lnJ, 4.8459, -4.1399},   {0.45, J1, 4.4944, -4.4192},
                            {0.49, lnJ, 0.9802, -0.9442},   {0.49, J1, 0.9621, -0.9614},
                            {0.499, lnJ, 0.0981, -0.0977},  {0.499, J1, 0.0979, -0.0979}};
  for (const ColumnRow& row : rows) {
    const double K = bulk_modulus(row.nu);
    const ConfinedColumn hanging(row.law, kMu, K, kRhoG, 0.1, +1), standing(row.law, kMu, K, kRhoG, 0.1, -1);
    EXPECT_NEAR(1e3 * hanging.tip(), row.hanging_mm, test::kQuotedFourDecimalsMm) << law_tag(row.law) << row.nu;
    EXPECT_NEAR(1e3 * standing.tip(), row.standing_mm, test::kQuotedFourDecimalsMm) << law_tag(row.law) << row.nu;
  }
  // The small-load limit is the linear confined column delta = rho g L^2 / (2M), M = K + 4mu/3,
  // tabulated as 14.0143 / 4.4591 / 0.9618 / 0.0979 mm (at 1e-6 g, then scaled back).
  const double linear_mm[][2] = {{0.30, 14.0143}, {0.45, 4.4591}, {0.49, 0.9618}, {0.499, 0.0979}};
  for (const auto& [nu, table_mm] : linear_mm) {
    const double M = bulk_modulus(nu) + 4.0 * kMu / 3.0, delta_mm = 1e3 * kRhoG * 0.01 / (2.0 * M);
    EXPECT_NEAR(delta_mm, table_mm, test::kQuotedFourDecimalsMm) << nu;
    for (MaterialLaw law : {lnJ, J1}) {
      const ConfinedColumn tiny(law, kMu, bulk_modulus(nu), 1e-6 * kRhoG, 0.1, +1);
      EXPECT_NEAR(1e9 * tiny.tip(), delta_mm, test::kSmallLoadLinearityRel * delta_mm) << law_tag(law) << nu;
    }
  }
}

struct UniaxialRow {
  MaterialLaw law;
  double nu, lambda, P11_Pa, lateral, J;
};

/// Uniaxial table (mu = 1000 Pa), FEBio lnJ and NiftySim (J-1)^2, nu = 0.49 (docs/verification.md,
/// "Solver: analytic references").
const UniaxialRow kUniaxialTable[] = {
    {MaterialLaw::CompressibleNeoHookean, 0.49, 1.2, 503.229, 0.914399, 1.003350},
    {MaterialLaw::CompressibleNeoHookean, 0.49, 1.5, 1052.563, 0.819241, 1.006734},
    {MaterialLaw::CompressibleNeoHookean, 0.49, 2.0, 1747.462, 0.710687, 1.010152},
    {MaterialLaw::NeoHookean, 0.49, 1.2, 501.419, 0.914705, 1.004022},
    {MaterialLaw::NeoHookean, 0.49, 1.5, 1043.711, 0.820731, 1.010399},
    {MaterialLaw::NeoHookean, 0.49, 2.0, 1718.609, 0.715038, 1.022560},
};

TEST(VerificationColumnReference, ReproducesTheUniaxialTable) {
  for (const UniaxialRow& row : kUniaxialTable) {
    const test::UniaxialState st = test::uniaxial_stress(row.law, kMu, bulk_modulus(row.nu), row.lambda);
    const std::string what = std::string(law_tag(row.law)) + " lambda " + std::to_string(row.lambda);
    EXPECT_NEAR(st.P11, row.P11_Pa, test::kQuotedSixDigitsRel * row.P11_Pa) << what;
    EXPECT_NEAR(st.lateral_stretch, row.lateral, test::kQuotedSixDigitsRel * row.lateral) << what;
    EXPECT_NEAR(st.J, row.J, test::kQuotedSixDigitsRel * row.J) << what;
  }
  // nu = 0.45, lambda = 2: lnJ 1736.509, (J-1)^2 1617.251 Pa.
  EXPECT_NEAR(test::uniaxial_stress(MaterialLaw::CompressibleNeoHookean, kMu, bulk_modulus(0.45), 2.0).P11, 1736.509,
              test::kQuotedSixDigitsRel * 1736.509);
  EXPECT_NEAR(test::uniaxial_stress(MaterialLaw::NeoHookean, kMu, bulk_modulus(0.45), 2.0).P11, 1617.251,
              test::kQuotedSixDigitsRel * 1617.251);
}

// ---- 1. finite-strain confined column -------------------------------------------------------------

struct ColumnCase {
  MaterialLaw law;
  double nu;
  int sign;  ///< +1 hanging (support on top, tension), -1 standing (support below, compression)
  ElementOrder order;
};

std::string column_name(const ColumnCase& c) {
  std::ostringstream s;
  s << law_tag(c.law) << "_nu" << std::lround(100 * c.nu) << (c.sign > 0 ? "_hanging_" : "_standing_")
    << order_tag(c.order);
  return s.str();
}

// 10 x 10 mm cross-section, 100 mm long along z, gravity -z, on n x n x 5n cells (10/n x 10/n x
// 20/n mm). The four lateral faces are on frictionless rollers (sliding sets, normals x and y: the
// edge nodes lie on two of them and keep only z), the supported end is fixed (u = 0 is the exact
// solution's value there, lateral components included), the other end is free: the exact
// solution F = diag(1, 1, a(Z)) satisfies every condition, so it is the 3D solution.
// The refinement is uniform in all three directions: refining along z alone leaves an error of
// O(h_z h_xy) at the free end, where the Kuhn split hands the two ends of each cell's diagonal 1/12
// and 1/4 of the cell's weight instead of 1/6 each (in the interior the cells above and below
// make up for it), and the observed rates then fall towards 1 (measured on 2 x 2 x 10..80 cells:
// L2 rates down to 1.1-1.6 at the last refinement).
constexpr double kColumnWidthMm = 10.0, kColumnLengthMm = 100.0;
constexpr int kColumnAspect = 5;

Model column_model(const ColumnCase& c, int n) {
  const TetMesh mesh =
      test::box_mesh(Vector3d::Zero(), Vector3d(kColumnWidthMm, kColumnWidthMm, kColumnLengthMm), n, n, kColumnAspect * n);
  ModelSettings s = settings(c.order, Vector3d(0, 0, -1));
  const Vector3d ex = Vector3d::UnitX(), ey = Vector3d::UnitY(), ez = Vector3d::UnitZ();
  const Vector3d support = c.sign > 0 ? Vector3d(kColumnLengthMm * ez) : Vector3d::Zero();
  s.node_sets = {plane_set("roller_x0", Vector3d::Zero(), ex, Constraint::Sliding),
                 plane_set("roller_x1", kColumnWidthMm * ex, ex, Constraint::Sliding),
                 plane_set("roller_y0", Vector3d::Zero(), ey, Constraint::Sliding),
                 plane_set("roller_y1", kColumnWidthMm * ey, ey, Constraint::Sliding),
                 plane_set("support", support, ez, Constraint::Fixed)};
  return build(mesh, s, neo_hookean(c.law, c.nu));
}

/// Errors on meshes refined by 2: each below the previous one, and the last observed rate within
/// kConvergenceRateSlack of `expected`.
void expect_convergence(const std::vector<double>& errors, double expected, const std::string& what) {
  for (std::size_t i = 1; i < errors.size(); ++i)
    EXPECT_LT(errors[i], errors[i - 1]) << what << ": error does not decrease at refinement " << i;
  const std::vector<double> r = rates(errors);
  ASSERT_FALSE(r.empty());
  EXPECT_NEAR(r.back(), expected, test::kConvergenceRateSlack) << what << ": rates " << join(r);
}

void PrintTo(const ColumnCase& c, std::ostream* os) { *os << column_name(c); }

class VerificationConfinedColumn : public ::testing::TestWithParam<ColumnCase> {};

// Tip displacement (mean over the free-end nodes) and the L2 error of u over the volume converge
// at O(h^2) for tet4 and O(h^3) for tet10 (a is not polynomial, so neither space holds the
// solution). Every solve also balances: reactions + weight = 0, and the fixed end alone carries
// the weight (a roller that held tangentially would take part of it).
TEST_P(VerificationConfinedColumn, ConvergesToTheExactSolution) {
  const ColumnCase c = GetParam();
  const ConfinedColumn exact(c.law, kMu, bulk_modulus(c.nu), kRhoG, kColumnLengthMm / 1e3, c.sign);
  const double support_z = c.sign > 0 ? kColumnLengthMm : 0.0, tip_z = kColumnLengthMm - support_z;
  // u_z(Z) in mm, s the distance from the free end: hanging U(s) - Delta, standing Delta - U(s).
  auto exact_u = [&](const Vector3d& X) {
    const double s = std::abs(X.z() - tip_z) / 1e3;
    return Vector3d(0, 0, 1e3 * c.sign * (exact.extension(s) - exact.tip()));
  };
  const double tip_exact_mm = 1e3 * exact.tip();
  const double W = kRhoG * kColumnWidthMm * kColumnWidthMm * kColumnLengthMm * 1e-9;  // N
  const std::vector<int> cells =
      c.order == ElementOrder::Linear ? std::vector<int>{1, 2, 4, 8} : std::vector<int>{1, 2, 4};
  std::vector<double> tip_err, l2_err;
  for (int n : cells) {
    const Model model = column_model(c, n);
    const SolveResult r = solve_static(model, single_thread());
    ASSERT_TRUE(r.converged) << r.message;
    EXPECT_NEAR(r.total_load.z(), -W, test::kRelativeRoundoff * W);
    const double imbalance = reaction_imbalance(r, W);
    EXPECT_LE(imbalance, test::kSolverEquilibriumRel);
    double support_force = 0.0;
    for (const NodeReaction& f : r.reactions)
      if (near(model.nodes[f.node].z(), support_z)) support_force += f.force.z();
    EXPECT_NEAR(support_force, W, test::kSolverEquilibriumRel * W);

    double tip_sum = 0.0;
    int tip_nodes = 0;
    for (std::size_t v = 0; v < model.nodes.size(); ++v)
      if (near(model.nodes[v].z(), tip_z)) {
        tip_sum += r.displacements[v].z();
        ++tip_nodes;
      }
    const double tip_mm = -c.sign * tip_sum / tip_nodes;  // Delta: extension (+) or shortening (-)
    tip_err.push_back(std::abs(tip_mm - tip_exact_mm));
    l2_err.push_back(l2_error(model, r.displacements, exact_u).relative());
    std::cout << "[ verify   ] column " << column_name(c) << " " << n << "x" << n << "x" << kColumnAspect * n
              << " cells: tip " << std::setprecision(10) << tip_mm << " mm (exact " << tip_exact_mm << "), tip error "
              << std::setprecision(3) << tip_err.back() << " mm, relative L2 error " << l2_err.back()
              << ", reaction imbalance " << imbalance << ", " << r.total_iterations << " Newton its\n";
  }
  std::cout << "[ verify   ] column " << column_name(c) << " rates: tip " << join(rates(tip_err)) << "; L2 "
            << join(rates(l2_err)) << "\n";
  const double p = c.order == ElementOrder::Linear ? 2.0 : 3.0;
  expect_convergence(tip_err, p, column_name(c) + " tip");
  expect_convergence(l2_err, p, column_name(c) + " L2");
}

std::vector<ColumnCase> column_cases() {
  std::vector<ColumnCase> cases;
  for (ElementOrder order : {ElementOrder::Linear, ElementOrder::Quadratic})
    for (double nu : {0.30, 0.45})
      for (MaterialLaw law : {MaterialLaw::CompressibleNeoHookean, MaterialLaw::NeoHookean})
        for (int sign : {+1, -1}) cases.push_back({law, nu, sign, order});
  return cases;
}

INSTANTIATE_TEST_SUITE_P(Verification, VerificationConfinedColumn, ::testing::ValuesIn(column_cases()),
                         [](const auto& info) { return column_name(info.param); });

// ---- 2. small-strain hanging bar -----------------------------------------------------------------
// 20 x 20 mm cross-section centred on the z axis, 0 <= z <= 40 mm, m x m x 2m cells, gravity -z,
// nu = 0.3. No node set: every node of the face z = L is prescribed the exact displacement (lateral
// contraction included), the rest is free. The solves run at a small gravity scale (prescribed
// values scaled alike), where the neo-Hookean laws reduce to linear elasticity with their mu and
// K (E = 9 K mu / (3K + mu), nu = (3K - 2mu) / (2 (3K + mu))).

constexpr double kBarHalfWidthMm = 10.0, kBarLengthMm = 40.0, kBarNu = 0.30;
/// Gravity (and prescribed motion) scale of the linear checks: largest strain rho g L / E * s ~ 1.5e-4.
constexpr double kBarGravityScale = 1e-3;

/// Exact linear solution (Timoshenko & Goodier, "Theory of Elasticity") at full gravity:
/// bar 0 <= z <= L hanging from z = L, gravity -z. X and u in mm.
Vector3d bar_exact(const Vector3d& X, double E, double nu) {
  const double x = X.x() / 1e3, y = X.y() / 1e3, z = X.z() / 1e3, L = kBarLengthMm / 1e3, b = kRhoG / E;
  return 1e3 * Vector3d(-nu * b * x * z, -nu * b * y * z, b * z * z / 2 + nu * b * (x * x + y * y) / 2 - b * L * L / 2);
}

Model bar_model(ElementOrder order, int m, MaterialLaw law) {
  const Vector3d lo(-kBarHalfWidthMm, -kBarHalfWidthMm, 0.0), hi(kBarHalfWidthMm, kBarHalfWidthMm, kBarLengthMm);
  Model model = build(test::box_mesh(lo, hi, m, m, 2 * m), settings(order, Vector3d(0, 0, -1)), neo_hookean(law, kBarNu));
  model.analysis.load_steps = 1;
  return model;
}

SolveResult bar_solve(const Model& model, double scale) {
  const MaterialSpec& spec = model.materials.at(0);
  SolveOptions o = single_thread();
  o.gravity_scale = scale;
  for (std::size_t v = 0; v < model.nodes.size(); ++v)
    if (near(model.nodes[v].z(), kBarLengthMm))
      o.prescribed.push_back(
          {static_cast<int>(v), scale * bar_exact(model.nodes[v], spec.young_modulus_Pa(), spec.poisson_ratio())});
  return solve_static(model, o);
}

/// The linear response (per unit gravity scale) of the bar of `model`, extrapolated from two
/// solves: u(s) = s u1 + s^2 u2 + s^3 u3 + ..., so (4 u(s) - u(2s)) / (2s) = u1 - 2 s^2 u3: the
/// neo-Hookean nonlinearity drops out to O(s^2) (relative 0.4-1 eps^2 measured, eps the largest
/// strain). A single solve at a smaller scale cannot do as well: its error is O(eps), and below
/// s ~ 1e-4 the relative residual cannot reach kSolverTightResidualRel any more (the round-off of
/// S(C) near C = I is absolute, ~1e-16 mu, while the load shrinks with s: measured, s = 1e-5 stalls
/// at 3e-6 of the load after the cut-backs).
std::vector<Vector3d> bar_linear_response(const Model& model, const std::string& what) {
  constexpr double s = kBarGravityScale;
  const SolveResult a = bar_solve(model, s), b = bar_solve(model, 2 * s);
  EXPECT_TRUE(a.converged && b.converged) << a.message << " / " << b.message;
  const double W = kRhoG * 4 * kBarHalfWidthMm * kBarHalfWidthMm * kBarLengthMm * 1e-9;  // N at full gravity
  for (const SolveResult* r : {&a, &b}) {
    const double imbalance = reaction_imbalance(*r, (r == &a ? s : 2 * s) * W);
    EXPECT_LE(imbalance, test::kSolverEquilibriumRel) << what;
    std::cout << "[ verify   ] hanging bar " << what << (r == &a ? " at s" : " at 2s") << ": reaction imbalance "
              << std::setprecision(3) << imbalance << ", " << r->total_iterations << " Newton its\n";
  }
  std::vector<Vector3d> u(model.nodes.size());
  for (std::size_t v = 0; v < u.size(); ++v) u[v] = (4 * a.displacements[v] - b.displacements[v]) / (2 * s);
  return u;
}

std::function<Vector3d(const Vector3d&)> bar_exact_of(const Model& model) {
  const double E = model.materials.at(0).young_modulus_Pa(), nu = model.materials.at(0).poisson_ratio();
  return [E, nu](const Vector3d& X) { return bar_exact(X, E, nu); };
}

/// Node at X (mm), -1 if none.
int node_at(const Model& model, const Vector3d& X) {
  for (std::size_t v = 0; v < model.nodes.size(); ++v)
    if ((model.nodes[v] - X).norm() <= 1e-9) return static_cast<int>(v);
  return -1;
}

// tet4 converges at O(h^2) in L2 and at the corner node. It is far from asymptotic on coarse
// meshes of this bar (measured L2 rates 0.59, 1.17, 1.67, 1.90 from 1 to 16 cells across, 1.97
// from 16 to 24), hence 2..16 cells across (49k tets at the finest, the largest solve of the suite).
TEST(VerificationHangingBar, Tet4ConvergesAtSecondOrderWithPoissonContraction) {
  // Corner at mid-height: u_x = -nu rho g x z / E there (-0.226 mm at full gravity), which the
  // 1-D bar formula (u_x = 0) misses entirely: a solver without the Poisson coupling would stay
  // at relative error 1 there.
  const Vector3d corner(kBarHalfWidthMm, kBarHalfWidthMm, kBarLengthMm / 2);
  std::vector<double> l2, corner_err;
  double corner_exact = 0.0;
  for (int m : {2, 4, 8, 16}) {
    const Model model = bar_model(ElementOrder::Linear, m, MaterialLaw::CompressibleNeoHookean);
    const std::string what = "tet4 " + std::to_string(m) + "x" + std::to_string(m) + "x" + std::to_string(2 * m);
    const std::vector<Vector3d> u = bar_linear_response(model, what);
    const auto exact = bar_exact_of(model);
    l2.push_back(l2_error(model, u, exact).relative());
    const int v = node_at(model, corner);
    ASSERT_GE(v, 0);
    corner_exact = exact(corner).x();
    corner_err.push_back(std::abs(u[v].x() - corner_exact) / std::abs(corner_exact));
    std::cout << "[ verify   ] hanging bar " << what << ": relative L2 error " << std::setprecision(4) << l2.back()
              << ", corner u_x " << u[v].x() << " mm (exact " << corner_exact << "), relative error "
              << corner_err.back() << "\n";
  }
  std::cout << "[ verify   ] hanging bar tet4 rates: L2 " << join(rates(l2)) << "; corner u_x "
            << join(rates(corner_err)) << "\n";
  expect_convergence(l2, 2.0, "hanging bar tet4 L2");
  expect_convergence(corner_err, 2.0, "hanging bar tet4 corner u_x");
}

TEST(VerificationHangingBar, Tet10ReproducesTheQuadraticSolutionExactly) {
  // The exact field is a quadratic polynomial and the prescribed face values are exact at the
  // midside nodes too, so the tet10 space contains it: the error is only what is left of the
  // nonlinearity and round-off, not a discretisation error (no rate to measure; tet10's O(h^3)
  // is measured on the confined column).
  for (MaterialLaw law : {MaterialLaw::CompressibleNeoHookean, MaterialLaw::NeoHookean})
    for (int m : {1, 2}) {
      const Model model = bar_model(ElementOrder::Quadratic, m, law);
      const std::string what = std::string("tet10 ") + law_tag(law) + " " + std::to_string(m) + "x" +
                               std::to_string(m) + "x" + std::to_string(2 * m);
      const std::vector<Vector3d> u = bar_linear_response(model, what);
      const auto exact = bar_exact_of(model);
      const double rel = l2_error(model, u, exact).relative();
      double nodal = 0.0, scale = 0.0;
      for (std::size_t v = 0; v < u.size(); ++v) {
        nodal = std::max(nodal, (u[v] - exact(model.nodes[v])).norm());
        scale = std::max(scale, exact(model.nodes[v]).norm());
      }
      std::cout << "[ verify   ] hanging bar " << what << ": relative L2 error " << std::setprecision(3) << rel
                << ", max nodal error / max |u| " << nodal / scale << "\n";
      EXPECT_LE(rel, test::kLinearPartRel) << what;
      EXPECT_LE(nodal, test::kLinearPartRel * scale) << what;
    }
}

// ---- 4. homogeneous uniaxial stress ------------------------------------------------------------

struct UniaxialCase {
  UniaxialRow row;
  ElementOrder order;
};

std::string uniaxial_name(const UniaxialCase& c) {
  std::ostringstream s;
  s << law_tag(c.row.law) << "_stretch" << std::lround(10 * c.row.lambda) << "_" << order_tag(c.order);
  return s.str();
}

void PrintTo(const UniaxialCase& c, std::ostream* os) { *os << uniaxial_name(c); }

class VerificationUniaxial : public ::testing::TestWithParam<UniaxialCase> {};

// A 10 mm cube (2 x 2 x 2 cells, the centre node moved off the grid so that no element is a
// Kuhn tetrahedron of the regular grid any more) stretched along x: the face x = 0 on rollers
// (normal x, free to contract), the face x = 10 mm prescribed the homogeneous motion
// ((lambda - 1) X, (b - 1) Y, (b - 1) Z) with b the reference lateral stretch, the four lateral
// faces free, no gravity. The homogeneous state is admissible, and it is the solution only if
// the solver's law has P22 = P33 = 0 at (lambda, b, b): otherwise the free lateral faces would
// bulge or neck and the roller face nodes would not sit at Y b, Z b. Every element stays
// straight, so tet4 and tet10 reproduce it exactly (up to the solver tolerance).
TEST_P(VerificationUniaxial, ReactionIsP11AndFreeFacesContract) {
  const UniaxialCase c = GetParam();
  const double side = 10.0, K = bulk_modulus(c.row.nu), lambda = c.row.lambda;
  const test::UniaxialState ref = test::uniaxial_stress(c.row.law, kMu, K, lambda);
  TetMesh mesh = test::box_mesh(Vector3d::Zero(), Vector3d(side, side, side), 2, 2, 2);
  mesh.points[13] += Vector3d(0.4, -0.3, 0.5);  // the centre node (1,1,1) of the 3 x 3 x 3 grid
  ModelSettings s = settings(c.order, Vector3d::Zero());
  s.node_sets = {plane_set("roller_x0", Vector3d::Zero(), Vector3d::UnitX(), Constraint::Sliding)};
  const Model model = build(mesh, s, neo_hookean(c.row.law, c.row.nu));
  const double b = ref.lateral_stretch;
  SolveOptions o = single_thread();
  for (std::size_t v = 0; v < model.nodes.size(); ++v)
    if (near(model.nodes[v].x(), side)) {
      const Vector3d& X = model.nodes[v];
      o.prescribed.push_back({static_cast<int>(v), Vector3d((lambda - 1) * X.x(), (b - 1) * X.y(), (b - 1) * X.z())});
    }
  const SolveResult r = solve_static(model, o);
  ASSERT_TRUE(r.converged) << r.message;
  EXPECT_EQ(r.total_load, Vector3d::Zero());
  // Axial force on the pulled face / reference area = P11 (N / mm^2 = MPa -> Pa).
  double pulled = 0.0, roller = 0.0;
  for (const NodeReaction& f : r.reactions) (near(model.nodes[f.node].x(), side) ? pulled : roller) += f.force.x();
  const double P11 = pulled / (side * side) * 1e6;
  const double imbalance = reaction_imbalance(r, std::abs(pulled));
  // Lateral stretch of every node that is free to contract (all but the prescribed face).
  double worst_b = 0.0, worst_axial = 0.0, worst_ref = 0.0;
  for (std::size_t v = 0; v < model.nodes.size(); ++v) {
    const Vector3d& X = model.nodes[v];
    const Vector3d& u = r.displacements[v];
    if (X.x() > 0) worst_axial = std::max(worst_axial, std::abs(u.x() / X.x() + 1 - lambda) / lambda);
    if (near(X.x(), side)) continue;
    for (int i : {1, 2})
      if (X[i] > 0) {
        worst_b = std::max(worst_b, std::abs(u[i] / X[i] + 1 - c.row.lateral) / c.row.lateral);
        worst_ref = std::max(worst_ref, std::abs(u[i] / X[i] + 1 - b) / b);
      }
  }
  std::cout << "[ verify   ] uniaxial " << uniaxial_name(c) << ": P11 " << std::setprecision(9) << P11 << " Pa (table "
            << c.row.P11_Pa << ", computed " << ref.P11 << "), lateral stretch worst relative deviation from "
            << c.row.lateral << ": " << std::setprecision(3) << worst_b << " (from the computed "
            << std::setprecision(9) << b << ": " << std::setprecision(3) << worst_ref << "), axial " << worst_axial
            << ", reaction imbalance " << imbalance << ", " << r.total_iterations << " Newton its\n";
  // Against the table (its 6 digits), and against the computed reference to the solver's accuracy:
  // the homogeneous state is exact in both spaces, so only the solver tolerance separates them.
  EXPECT_NEAR(P11, c.row.P11_Pa, test::kQuotedSixDigitsRel * c.row.P11_Pa);
  EXPECT_NEAR(P11, ref.P11, test::kHomogeneousStateRel * ref.P11);
  EXPECT_LE(worst_ref, test::kHomogeneousStateRel);
  EXPECT_GT(pulled, 0.0);
  EXPECT_NEAR(roller, -pulled, test::kSolverEquilibriumRel * std::abs(pulled));
  EXPECT_LE(imbalance, test::kSolverEquilibriumRel);
  EXPECT_LE(worst_b, test::kQuotedSixDigitsRel);
  EXPECT_LE(worst_axial, test::kHomogeneousStateRel);
}

std::vector<UniaxialCase> uniaxial_cases() {
  std::vector<UniaxialCase> cases;
  for (ElementOrder order : {ElementOrder::Linear, ElementOrder::Quadratic})
    for (const UniaxialRow& row : kUniaxialTable) cases.push_back({row, order});
  return cases;
}

INSTANTIATE_TEST_SUITE_P(Verification, VerificationUniaxial, ::testing::ValuesIn(uniaxial_cases()),
                         [](const auto& info) { return uniaxial_name(info.param); });

}  // namespace
}  // namespace tissuemesh
