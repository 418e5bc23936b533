// The radius-edge ratio a surface forces on a tet mesh keeping its triangles
// (volume/forced_radius_edge.h): the closed form 1 / (2 sin theta_min) on hand-made triangles,
// found by its smallest angle wherever that sits, and the invariant that TetGen's -Y mesh never
// gets below it (on the test complexes and on a closed surface whose thin face forces more than
// -q2).
#include "core/errors.h"
#include "volume/forced_radius_edge.h"
#include "quality/mesh_quality.h"
#include "volume/tetgen_mesher.h"
#include "support/complex_meshes.h"
#include "support/tolerances.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <cmath>
#include <iostream>

using namespace tissuemesh;
using namespace tissuemesh::test;
using Eigen::Vector3d;

namespace {

constexpr double kDeg = EIGEN_PI / 180.0;

/// Appends triangle (a, b, c) between regions p < q to s.
void add_triangle(TriSurface& s, const Vector3d& a, const Vector3d& b, const Vector3d& c, int p, int q) {
  const int n = static_cast<int>(s.points.size());
  s.points.insert(s.points.end(), {a, b, c});
  s.triangles.push_back({n, n + 1, n + 2});
  s.labels.push_back({p, q});
}

/// Circumradius over shortest edge of a triangle, by R = abc / (4 area): a route independent of
/// the angles the bound is computed from.
double circumradius_over_shortest(const Vector3d& a, const Vector3d& b, const Vector3d& c) {
  const double ab = (b - a).norm(), bc = (c - b).norm(), ca = (a - c).norm();
  const double area = 0.5 * (b - a).cross(c - a).norm();
  return ab * bc * ca / (4.0 * area) / std::min({ab, bc, ca});
}

}  // namespace

TEST(ForcedRadiusEdge, ThinTriangleSetsOneOverTwiceTheSineOfItsSmallestAngle) {
  // Three separate triangles: equilateral (1/sqrt 3), right isosceles (1/sqrt 2), and a scalene
  // one with angles 100, 10 and 70 degrees whose 10 degree angle is at its second corner, turned
  // out of the axes so that no coordinate is special.
  TriSurface s;
  s.tissue_names = {"a", "b"};
  add_triangle(s, {0, 0, 0}, {4, 0, 0}, {2, 2 * std::sqrt(3.0), 0}, 0, 1);
  add_triangle(s, {0, 0, 5}, {3, 0, 5}, {0, 3, 5}, 0, 2);
  const double length = 7.0, side = length * std::sin(70 * kDeg) / std::sin(100 * kDeg);
  const Eigen::Matrix3d turn = (Eigen::AngleAxisd(0.3, Vector3d(1, 2, 3).normalized())).toRotationMatrix();
  const Vector3d origin(10, -4, 2);
  const Vector3d a = origin + turn * Vector3d(side * std::cos(10 * kDeg), side * std::sin(10 * kDeg), 0),
                 b = origin, c = origin + turn * Vector3d(length, 0, 0);
  add_triangle(s, a, b, c, 1, 2);

  const ForcedRadiusEdge f = forced_radius_edge_ratio(s, 2.0);
  const double expected = 1.0 / (2.0 * std::sin(10 * kDeg));  // 2.8794
  EXPECT_NEAR(f.ratio, expected, kRelativeRoundoff * expected);
  EXPECT_NEAR(f.ratio, circumradius_over_shortest(a, b, c), kRelativeRoundoff * expected);
  EXPECT_EQ(f.triangle, 2);
  EXPECT_NEAR(f.min_angle_deg, 10.0, kAngleDeg);
  EXPECT_EQ(f.triangles_above_bound, 1u);
  // The other two triangles' own bounds order the counts: 1/sqrt 2 = 0.7071, 1/sqrt 3 = 0.5774.
  EXPECT_EQ(forced_radius_edge_ratio(s, 0.7).triangles_above_bound, 2u);
  EXPECT_EQ(forced_radius_edge_ratio(s, 0.5).triangles_above_bound, 3u);
  EXPECT_EQ(forced_radius_edge_ratio(s, expected * (1.0 + kRelativeRoundoff)).triangles_above_bound, 0u);

  // Without the thin one, the right isosceles triangle sets it.
  s.triangles.pop_back();
  s.labels.pop_back();
  const ForcedRadiusEdge g = forced_radius_edge_ratio(s, 2.0);
  EXPECT_NEAR(g.ratio, 1.0 / std::sqrt(2.0), kRelativeRoundoff);
  EXPECT_EQ(g.triangle, 1);
  EXPECT_NEAR(g.min_angle_deg, 45.0, kAngleDeg);
  EXPECT_EQ(g.triangles_above_bound, 0u);
}

TEST(ForcedRadiusEdge, EmptyFlatAndInvalidSurfaces) {
  TriSurface s;
  s.tissue_names = {"a"};
  const ForcedRadiusEdge none = forced_radius_edge_ratio(s, 2.0);
  EXPECT_EQ(none.ratio, 0.0);
  EXPECT_EQ(none.triangle, -1);
  EXPECT_TRUE(std::isnan(none.min_angle_deg));
  add_triangle(s, {0, 0, 0}, {1, 1, 1}, {2, 2, 2}, 0, 1);  // collinear: no tet can have it as a face
  EXPECT_TRUE(std::isinf(forced_radius_edge_ratio(s, 2.0).ratio));
  s.labels[0] = {1, 0};
  EXPECT_THROW(forced_radius_edge_ratio(s, 2.0), InputError);
}

TEST(ForcedRadiusEdge, TetgenNeverGoesBelowTheBoundItsInputForces) {
  Progress progress;
  // A single closed tissue: a tet whose 20 x 1.5 mm right-angled base has a 4.29 degree corner
  // (forcing 6.685), which TetGen must keep (-Y) and so cannot bring to its -q2. Faces wound
  // into the tissue (TriSurface: normal from p = outside into q = t1).
  TriSurface thin;
  thin.tissue_names = {"t1"};
  thin.points = {{0, 0, 0}, {20, 0, 0}, {20, 1.5, 0}, {12, 0.7, 6}};
  for (const std::array<int, 3>& k : {std::array<int, 3>{0, 1, 2}, {1, 3, 2}, {0, 2, 3}, {0, 3, 1}}) {
    thin.triangles.push_back(k);
    thin.labels.push_back({0, 1});
  }
  const struct {
    const char* name;
    TriSurface surface;
  } cases[] = {{"nested spheres", remeshed(nested_spheres(), 2, 300).surface},
               {"three boxes", remeshed(three_boxes(), 3, 400).surface},
               {"thin tet", thin}};
  for (const auto& c : cases) {
    const TetgenParams params;  // -q2
    const ForcedRadiusEdge forced = forced_radius_edge_ratio(c.surface, params.radius_edge_ratio);
    const TetgenResult tg = tetgen_mesh(c.surface, params, progress);
    const double measured = compute_quality(tg.mesh).total.max_radius_edge_ratio;
    std::cout << "[ forced   ] " << c.name << ": forced " << forced.ratio << " (" << forced.triangles_above_bound
              << " triangles above 2), TetGen max " << measured << "\n";
    EXPECT_GE(measured, forced.ratio * (1.0 - kRelativeRoundoff)) << c.name;
    if (forced.triangles_above_bound > 0) {
      EXPECT_GT(account_radius_edge_above(tg.mesh, c.surface, params.radius_edge_ratio).forced, 0u) << c.name;
    }
  }
  // The thin base forces more than the -q bound, so this case tests the bound, not -q.
  EXPECT_NEAR(forced_radius_edge_ratio(thin, 2.0).ratio, circumradius_over_shortest(thin.points[0], thin.points[1], thin.points[2]),
              kRelativeRoundoff * 6.7);
  EXPECT_EQ(forced_radius_edge_ratio(thin, 2.0).triangle, 0);
}

TEST(ForcedRadiusEdge, AccountSplitsTheTetsAboveTheBoundIntoForcedAndUnforced) {
  // Three separate tets of one tissue:
  // - "needle": on the thin 20 x 1.5 mm base of the test above (forces 6.685) with a tall apex;
  // - "cap": a 10 mm equilateral triangle and a point 0.5 mm above its centre (circumradius
  //   ~34 mm over a 5.8 mm shortest edge: ratio ~5.8), none of its faces thin (the sides' smallest
  //   angle is ~30 degrees, forcing ~1);
  // - "regular": the regular tet, ratio sqrt(6)/4.
  TetMesh mesh;
  mesh.tissue_names = {"t1"};
  auto add_tet = [&](std::array<Vector3d, 4> p) {
    if (signed_tet_volume(p[0], p[1], p[2], p[3]) < 0.0) std::swap(p[2], p[3]);
    const int n = static_cast<int>(mesh.points.size());
    mesh.points.insert(mesh.points.end(), p.begin(), p.end());
    mesh.tets.push_back({n, n + 1, n + 2, n + 3});
    mesh.tissue_ids.push_back(1);
  };
  add_tet({Vector3d(0, 0, 0), Vector3d(20, 0, 0), Vector3d(20, 1.5, 0), Vector3d(12, 0.7, 6)});
  add_tet({Vector3d(30, 0, 0), Vector3d(40, 0, 0), Vector3d(35, 5 * std::sqrt(3.0), 0),
           Vector3d(35, 5 / std::sqrt(3.0), 0.5)});
  add_tet({Vector3d(50, 0, 0), Vector3d(51, 0, 0), Vector3d(50.5, std::sqrt(3.0) / 2, 0),
           Vector3d(50.5, std::sqrt(3.0) / 6, std::sqrt(2.0 / 3.0))});
  std::vector<double> ratio;
  for (const auto& t : mesh.tets)
    ratio.push_back(tet_shape(mesh.points[t[0]], mesh.points[t[1]], mesh.points[t[2]], mesh.points[t[3]]).radius_edge_ratio);
  ASSERT_GT(ratio[1], 2.0);
  ASSERT_GT(ratio[0], ratio[1]);  // needle ~7.5, cap ~5.8
  ASSERT_LT(ratio[2], 2.0);

  // The surface: the needle's thin base (its own copies of the points, as interface_surface and
  // TetGen give them), the cap's base (not thin: it forces 1/sqrt 3), and a thin triangle
  // whose corners are not nodes of the mesh (it forces nothing there).
  TriSurface s;
  s.tissue_names = {"t1"};
  add_triangle(s, {0, 0, 0}, {20, 1.5, 0}, {20, 0, 0}, 0, 1);
  add_triangle(s, {30, 0, 0}, {35, 5 * std::sqrt(3.0), 0}, {40, 0, 0}, 0, 1);
  add_triangle(s, {100, 0, 0}, {120, 1.5, 0}, {120, 0, 0}, 0, 1);
  ASSERT_EQ(forced_radius_edge_ratio(s, 2.0).triangles_above_bound, 2u);

  const RadiusEdgeAccount a = account_radius_edge_above(mesh, s, 2.0);
  EXPECT_EQ(a.above, 2u);
  EXPECT_EQ(a.forced, 1u);  // the needle
  EXPECT_EQ(a.unforced, 1u);
  EXPECT_EQ(a.max_unforced_tet, 1);  // the cap
  EXPECT_NEAR(a.max_unforced_ratio, ratio[1], kRelativeRoundoff * ratio[1]);
  // The cap's base corners are nodes of the surface, its apex is not.
  EXPECT_EQ(a.unforced_by_surface_nodes, (std::array<std::size_t, 5>{0, 0, 0, 1, 0}));

  // The forced bound holds for the needle tet, as the header comment proves.
  EXPECT_GE(ratio[0], forced_radius_edge_ratio(s, 2.0).ratio * (1.0 - kRelativeRoundoff));

  // A bound above the cap's ratio leaves only the forced needle; a bound above both, nothing.
  const RadiusEdgeAccount b = account_radius_edge_above(mesh, s, ratio[1] * (1.0 + kRelativeRoundoff));
  EXPECT_EQ(b.above, 1u);
  EXPECT_EQ(b.forced, 1u);
  EXPECT_EQ(b.unforced, 0u);
  EXPECT_EQ(b.max_unforced_tet, -1);
  EXPECT_EQ(b.max_unforced_ratio, 0.0);
  const RadiusEdgeAccount none = account_radius_edge_above(mesh, s, ratio[0] * 2.0);
  EXPECT_EQ(none.above, 0u);
  EXPECT_EQ(none.forced, 0u);

  // Without the thin base in the surface, the needle is the mesher's own doing.
  TriSurface no_base = s;
  no_base.triangles.erase(no_base.triangles.begin());
  no_base.labels.erase(no_base.labels.begin());
  const RadiusEdgeAccount c = account_radius_edge_above(mesh, no_base, 2.0);
  EXPECT_EQ(c.forced, 0u);
  EXPECT_EQ(c.unforced, 2u);
  EXPECT_EQ(c.max_unforced_tet, 0);
  EXPECT_EQ(c.unforced_by_surface_nodes, (std::array<std::size_t, 5>{1, 0, 0, 1, 0}));  // needle: none left

  // A flat tet (four coplanar nodes, none on the surface) counts, with ratio +infinity.
  TetMesh with_flat = mesh;
  with_flat.points.insert(with_flat.points.end(), {Vector3d(60, 0, 0), Vector3d(61, 0, 0), Vector3d(61, 1, 0), Vector3d(60, 1, 0)});
  with_flat.tets.push_back({12, 13, 14, 15});
  with_flat.tissue_ids.push_back(1);
  const RadiusEdgeAccount f = account_radius_edge_above(with_flat, s, 2.0);
  EXPECT_EQ(f.above, 3u);
  EXPECT_EQ(f.unforced, 2u);
  EXPECT_TRUE(std::isinf(f.max_unforced_ratio));
  EXPECT_EQ(f.max_unforced_tet, 3);
  EXPECT_EQ(f.unforced_by_surface_nodes, (std::array<std::size_t, 5>{1, 0, 0, 1, 0}));

  // Invalid input is refused.
  TriSurface bad = s;
  bad.labels[0] = {1, 0};
  EXPECT_THROW(account_radius_edge_above(mesh, bad, 2.0), InputError);
  TetMesh bad_mesh = mesh;
  bad_mesh.tets[0][3] = 99;  // no such node
  EXPECT_THROW(account_radius_edge_above(bad_mesh, s, 2.0), InputError);
}
