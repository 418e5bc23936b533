// FreeCellDomain (volume/free_cell_domain.h): the same region and surface-intersection answers as
// CGAL's Polyhedral_complex_mesh_domain_3, and the same draws from CGAL's default random
// generator, on two nested cubes (tests/support/nested_cubes.h); the answers also match the
// cubes' exact regions; and the same patch seeds as CGAL's on two nested spheres partly covered
// by protecting balls. That sameness is why the volume meshes stay bit-identical.
#include "volume/free_cell_domain.h"

#include "support/nested_cubes.h"

#include <CGAL/Mesh_complex_3_in_triangulation_3.h>
#include <CGAL/Mesh_polyhedron_3.h>
#include <CGAL/Mesh_triangulation_3.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <tuple>
#include <utility>
#include <vector>

using namespace tissuemesh;
using tissuemesh::test::NestedCubes;

namespace {

using Polyhedron = CGAL::Mesh_polyhedron_3<CGAL::Epick>::type;
using Point = CGAL::Epick::Point_3;

// One polyhedron per cube (its 12 triangles), with the cube's region pair.
struct CubePolyhedra {
  std::vector<Polyhedron> polyhedra;
  std::vector<std::pair<int, int>> sides;
  explicit CubePolyhedra(const TriSurface& s) {
    for (int cube = 0; cube < 2; ++cube) {
      std::vector<Point> points;
      for (int c = 0; c < 8; ++c) {
        const Eigen::Vector3d& p = s.points[static_cast<std::size_t>(8 * cube + c)];
        points.emplace_back(p.x(), p.y(), p.z());
      }
      std::vector<std::vector<std::size_t>> polygons;
      for (int t = 12 * cube; t < 12 * cube + 12; ++t) {
        const auto& tri = s.triangles[static_cast<std::size_t>(t)];
        polygons.push_back({std::size_t(tri[0] - 8 * cube), std::size_t(tri[1] - 8 * cube), std::size_t(tri[2] - 8 * cube)});
      }
      polyhedra.emplace_back();
      CGAL::Polygon_mesh_processing::polygon_soup_to_polygon_mesh(points, polygons, polyhedra.back());
      sides.emplace_back(s.labels[static_cast<std::size_t>(12 * cube)][0], s.labels[static_cast<std::size_t>(12 * cube)][1]);
    }
  }
};

int region_of(const ComplexDomain::Subdomain& s) { return s ? *s : 0; }

}  // namespace

TEST(FreeCellDomain, SameAnswersAndSameRandomDrawsAsCgalsDomain) {
  const NestedCubes cubes;
  CubePolyhedra input(cubes.surface);
  const ComplexDomain cgal(input.polyhedra.begin(), input.polyhedra.end(), input.sides.begin(), input.sides.end());
  FreeCellDomain fast(input.polyhedra.begin(), input.polyhedra.end(), input.sides.begin(), input.sides.end());
  const auto [grid, unknown] = fast.index_regions(cubes.surface, 1.3);
  EXPECT_EQ(unknown, 0u);

  std::mt19937 rng(5);
  std::uniform_real_distribution<double> coordinate(-30, 30), offset(-5, 5);
  std::vector<Point> points;
  std::vector<CGAL::Epick::Segment_3> segments;
  std::size_t in_free = 0;
  for (int n = 0; n < 20000; ++n) {
    const Point p(coordinate(rng), coordinate(rng), coordinate(rng));
    points.push_back(p);
    segments.emplace_back(p, Point(p.x() + offset(rng), p.y() + offset(rng), p.z() + offset(rng)));
    in_free += grid->component(Eigen::Vector3d(p.x(), p.y(), p.z())) >= 0;
  }
  ASSERT_GT(in_free, 10000u);  // most points take the grid's path

  CGAL::Random::State start;
  CGAL::get_default_random().save_state(start);
  std::vector<int> expected;
  for (const Point& p : points) expected.push_back(region_of(cgal.is_in_domain_object()(p)));
  const CGAL::Random after_cgal = CGAL::get_default_random();
  CGAL::get_default_random().restore_state(start);
  for (std::size_t k = 0; k < points.size(); ++k) {
    const Point& p = points[k];
    ASSERT_EQ(region_of(fast.is_in_domain_object()(p)), expected[k]) << "point " << k;
    EXPECT_EQ(expected[k], cubes.region(Eigen::Vector3d(p.x(), p.y(), p.z())));
  }
  EXPECT_TRUE(CGAL::get_default_random() == after_cgal) << "the grid's path drew differently from CGAL's";

  for (const auto& s : segments) {
    const auto a = cgal.construct_intersection_object()(s);
    const auto b = fast.construct_intersection_object()(s);
    ASSERT_EQ(std::get<2>(a), std::get<2>(b));
    if (std::get<2>(a) != 0) {
      EXPECT_EQ(std::get<0>(a), std::get<0>(b));
    }
  }
}

namespace {

// A closed UV sphere of radius r about c: rings x segments quads split into triangles, outward.
Polyhedron uv_sphere(double r, const Point& c, int rings, int segments) {
  std::vector<Point> points{Point(c.x(), c.y(), c.z() + r), Point(c.x(), c.y(), c.z() - r)};
  for (int i = 1; i < rings; ++i)
    for (int j = 0; j < segments; ++j) {
      const double theta = M_PI * i / rings, phi = 2 * M_PI * j / segments;
      points.emplace_back(c.x() + r * std::sin(theta) * std::cos(phi), c.y() + r * std::sin(theta) * std::sin(phi),
                          c.z() + r * std::cos(theta));
    }
  auto at = [&](int i, int j) { return std::size_t(2 + (i - 1) * segments + (j % segments)); };
  std::vector<std::vector<std::size_t>> polygons;
  for (int j = 0; j < segments; ++j) {
    polygons.push_back({0, at(1, j), at(1, j + 1)});
    polygons.push_back({1, at(rings - 1, j + 1), at(rings - 1, j)});
    for (int i = 1; i + 1 < rings; ++i) {
      polygons.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
      polygons.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
    }
  }
  Polyhedron p;
  CGAL::Polygon_mesh_processing::polygon_soup_to_polygon_mesh(points, polygons, p);
  return p;
}

}  // namespace

TEST(FreeCellDomain, PatchSeedsAreCgalsOnesOutsideEveryBall) {
  using Tr = CGAL::Mesh_triangulation_3<FreeCellDomain, CGAL::Default, CGAL::Sequential_tag>::type;
  using C3t3 = CGAL::Mesh_complex_3_in_triangulation_3<Tr, FreeCellDomain::Corner_index, FreeCellDomain::Curve_index>;
  std::vector<Polyhedron> spheres{uv_sphere(20, Point(0, 0, 0), 24, 48), uv_sphere(9, Point(2, -1, 3), 16, 32)};
  const std::vector<std::pair<int, int>> sides{{1, 0}, {2, 1}};
  FreeCellDomain domain(spheres.begin(), spheres.end(), sides.begin(), sides.end());
  domain.detect_borders();  // none on closed spheres: both patches are closed

  // The same balls (weighted points, as junction protection leaves them) in two complexes, over
  // sphere vertices, so that many of the spheres' vertices are inside one.
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> radius(1.0, 6.0);
  std::vector<CGAL::Epick::Sphere_3> balls;
  for (const Polyhedron& p : spheres) {
    std::size_t k = 0;
    for (auto v = p.vertices_begin(); v != p.vertices_end(); ++v, ++k)
      if (k % 37 == 0) balls.emplace_back(v->point(), std::pow(radius(rng), 2));
  }
  C3t3 by_cgal, by_grid;
  for (C3t3* c : {&by_cgal, &by_grid})
    for (const auto& b : balls) {
      const auto v = c->triangulation().insert(Tr::Weighted_point(b.center(), b.squared_radius()));
      c->set_dimension(v, 0);
    }
  const std::size_t before = by_cgal.triangulation().number_of_vertices();
  ASSERT_GT(before, 30u);
  domain.add_vertices_to_c3t3_on_patch_without_feature_edges(by_cgal);
  domain.add_patch_seeds(by_grid);

  auto seeds = [&](const C3t3& c) {
    std::vector<std::tuple<double, double, double, int>> out;
    for (auto v = c.triangulation().finite_vertices_begin(); v != c.triangulation().finite_vertices_end(); ++v)
      if (c.in_dimension(v) == 2) {
        const Point& p = c.triangulation().point(v).point();
        out.emplace_back(p.x(), p.y(), p.z(), domain.surface_patch_index(c.index(Tr::Vertex_handle(v))));
      }
    std::sort(out.begin(), out.end());
    return out;
  };
  const auto expected = seeds(by_cgal), got = seeds(by_grid);
  EXPECT_EQ(expected.size(), 40u);  // 20 per closed sphere
  EXPECT_EQ(got, expected);
  std::size_t held = 0;  // sphere vertices inside a ball: the test the grid answers must matter
  for (const Polyhedron& p : spheres)
    for (auto v = p.vertices_begin(); v != p.vertices_end(); ++v) {
      const bool inside = std::any_of(balls.begin(), balls.end(), [&](const auto& b) { return !b.has_on_unbounded_side(v->point()); });
      held += inside;
      if (inside) {
        for (const auto& s : got) EXPECT_NE(Point(std::get<0>(s), std::get<1>(s), std::get<2>(s)), v->point());
      }
    }
  EXPECT_GT(held, 200u);
}
