// FreeCellDomain (volume/free_cell_domain.h): the same region and surface-intersection answers as
// CGAL's Polyhedral_complex_mesh_domain_3, and the same draws from CGAL's default random
// generator, on two nested cubes (tests/support/nested_cubes.h); the answers also match the
// cubes' exact regions. That sameness is why the volume meshes stay bit-identical.
#include "volume/free_cell_domain.h"

#include "support/nested_cubes.h"

#include <CGAL/Mesh_polyhedron_3.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <gtest/gtest.h>

#include <random>
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
