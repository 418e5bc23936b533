// The multi-material surface of a tet mesh (quality/mesh_interfaces.h) on a hand-built conforming
// mesh: 2 x 2 x 1 unit cubes (Kuhn subdivision, 6 tets each) of tissues 1, 2, 3, 3. Exact
// volumes, the label pairs, closed tissues, junctions, and TetGen meshing the same geometry.
#include "core/errors.h"
#include "quality/conformity.h"
#include "quality/mesh_interfaces.h"
#include "quality/mesh_quality.h"
#include "quality/node_spacing.h"
#include "surface/surface_checks.h"
#include "volume/tetgen_mesher.h"
#include "support/tolerances.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <set>

using namespace tissuemesh;
using namespace tissuemesh::test;

namespace {

/// Cubes [i, i+1] x [j, j+1] x [0, 1] for i, j in {0, 1}; tissue of cube (i, j) = ids[2 j + i].
TetMesh cubes(const std::array<int, 4>& ids) {
  TetMesh m;
  m.tissue_names = {"a", "b", "c"};
  auto node = [](int x, int y, int z) { return x + 3 * y + 9 * z; };
  for (int z = 0; z < 2; ++z)
    for (int y = 0; y < 3; ++y)
      for (int x = 0; x < 3; ++x) m.points.emplace_back(x, y, z);
  const int perms[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 2; ++i)
      for (const auto& p : perms) {  // Kuhn: walk from (0,0,0) to (1,1,1) one axis at a time
        std::array<int, 3> c{i, j, 0};
        std::array<int, 4> tet;
        tet[0] = node(c[0], c[1], c[2]);
        for (int s = 0; s < 3; ++s) {
          ++c[p[s]];
          tet[s + 1] = node(c[0], c[1], c[2]);
        }
        if (signed_tet_volume(m.points[tet[0]], m.points[tet[1]], m.points[tet[2]], m.points[tet[3]]) < 0)
          std::swap(tet[2], tet[3]);
        m.tets.push_back(tet);
        m.tissue_ids.push_back(ids[2 * j + i]);
      }
  return m;
}

/// Tet volume per tissue id (index 0 unused), from the quality report's signed sums.
std::vector<double> tissue_volumes(const TetMesh& m) {
  std::vector<double> v(m.num_tissues() + 1, 0.0);
  for (const TissueQuality& t : compute_quality(m).tissues) v[t.id] = t.volume_mm3;
  return v;
}

}  // namespace

TEST(MeshInterfaces, EveryInterfaceOnceClosedTissuesExactVolumes) {
  const TetMesh m = cubes({1, 2, 3, 3});
  const TriSurface s = interface_surface(m);
  ASSERT_NO_THROW(s.validate("interfaces"));
  const std::set<std::array<int, 2>> pairs(s.labels.begin(), s.labels.end());
  EXPECT_EQ(pairs, (std::set<std::array<int, 2>>{{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}}));
  // Faces: outer boundary 16 unit squares, interfaces 1|2, 1|3, 2|3 one square each: 2 triangles per square.
  EXPECT_EQ(s.triangles.size(), 2u * (16 + 3));
  const SurfaceCheckReport checks = check_surface(s);
  EXPECT_TRUE(checks.valid());
  const double expected[] = {1.0, 1.0, 2.0};
  for (const TissueSurfaceCheck& c : checks.tissues)
    EXPECT_NEAR(c.volume_mm3, expected[c.tissue_id - 1], kRelativeRoundoff) << c.name;  // outward: positive
  // Where the three tissues meet: the vertical line x = y = 1, and on the outer faces the lines
  // between two tissues and outside.
  bool centre_line = false;
  for (const auto& line : s.junctions)
    for (std::size_t k = 0; k + 1 < line.size(); ++k) {
      const Eigen::Vector3d a = s.points[line[k]], b = s.points[line[k + 1]];
      centre_line = centre_line || (a.head<2>() == Eigen::Vector2d(1, 1) && b.head<2>() == Eigen::Vector2d(1, 1));
    }
  EXPECT_TRUE(centre_line);
}

TEST(MeshInterfaces, TetgenMeshesTheSameGeometry) {
  const TetMesh m = cubes({1, 2, 3, 3});
  Progress progress;
  const TetgenResult r = tetgen_mesh(interface_surface(m), TetgenParams{}, progress);
  EXPECT_TRUE(check_conformity(r.mesh).conforming());
  const std::vector<double> volume = tissue_volumes(r.mesh);
  EXPECT_NEAR(volume[1], 1.0, kRelativeRoundoff);
  EXPECT_NEAR(volume[2], 1.0, kRelativeRoundoff);
  EXPECT_NEAR(volume[3], 2.0, kRelativeRoundoff);
}

TEST(MeshInterfaces, TetgenSeedsEveryPieceOfATissue) {
  // A checkerboard: tissues 1 and 2 each in two cubes that touch only along the vertical centre
  // edge (a non-manifold tissue boundary, as CGAL meshes have). Each piece needs its own seed, or
  // TetGen leaves it without a tissue and it is dropped.
  TetMesh m = cubes({2, 1, 1, 2});
  m.tissue_names.pop_back();
  Progress progress;
  const TetgenResult r = tetgen_mesh(interface_surface(m), TetgenParams{}, progress);
  const std::vector<double> volume = tissue_volumes(r.mesh);
  EXPECT_NEAR(volume[1], 2.0, kRelativeRoundoff);
  EXPECT_NEAR(volume[2], 2.0, kRelativeRoundoff);
  EXPECT_TRUE(check_conformity(r.mesh).conforming());
}

TEST(MeshInterfaces, NodesOfTheSurfacePointsAndTheirLargestCircumradius) {
  const TetMesh m = cubes({1, 2, 3, 3});
  std::vector<int> node;
  const TriSurface s = interface_surface(m, &node);
  ASSERT_EQ(node.size(), s.points.size());
  for (std::size_t v = 0; v < s.points.size(); ++v) EXPECT_EQ(s.points[v], m.points[node[v]]);
  // The centre node (1, 1, 0.5) does not exist; every one of the 18 nodes is on the boundary.
  EXPECT_EQ(node.size(), 18u);
  // Every Kuhn tet of a unit cube has the cube's body diagonal as an edge and a right angle
  // opposite it in every face through it, so its circumsphere is the cube's: radius sqrt(3) / 2.
  const std::vector<double> radius = largest_incident_circumradius_mm(m);
  ASSERT_EQ(radius.size(), m.points.size());
  for (double r : radius) EXPECT_NEAR(r, std::sqrt(3.0) / 2.0, kRelativeRoundoff);
  // A right-corner tet of legs 4 at node 0 (its circumsphere is that of the 4 x 4 x 4 cube: radius
  // 2 sqrt 3) raises node 0 only; nodes in nothing but a flat tet (four points on a line) get 0.
  TetMesh grown = m;
  const int n = static_cast<int>(m.points.size());
  for (const Eigen::Vector3d& p : {Eigen::Vector3d(-4, 0, 0), Eigen::Vector3d(0, -4, 0), Eigen::Vector3d(0, 0, -4)})
    grown.points.push_back(p);
  for (int k = 0; k < 4; ++k) grown.points.emplace_back(7.0 + k, 7.0 + k, 7.0 + k);
  grown.tets.push_back({0, n, n + 1, n + 2});
  grown.tets.push_back({n + 3, n + 4, n + 5, n + 6});
  grown.tissue_ids.insert(grown.tissue_ids.end(), {1, 1});
  const std::vector<double> r = largest_incident_circumradius_mm(grown);
  EXPECT_NEAR(r[0], 2.0 * std::sqrt(3.0), kRelativeRoundoff);
  EXPECT_NEAR(r[n], 2.0 * std::sqrt(3.0), kRelativeRoundoff);
  EXPECT_NEAR(r[1], std::sqrt(3.0) / 2.0, kRelativeRoundoff);
  for (int k = 3; k < 7; ++k) EXPECT_EQ(r[n + k], 0.0);
}

TEST(MeshInterfaces, RefusesAFaceInThreeTets) {
  TetMesh m = cubes({1, 1, 1, 1});
  m.tets.push_back(m.tets.front());  // a duplicate tet: its faces are in three tets
  m.tissue_ids.push_back(1);
  EXPECT_THROW(interface_surface(m), InputError);
}
