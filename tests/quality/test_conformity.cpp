// Conformity: face matching, interface counts, and each defect (inverted, orphan, duplicate,
// degenerate, over-shared face, non-conforming interface) made on purpose in meshes of cubes cut
// into 5 tets, where the expected counts follow from the geometry (derivations in comments).
#include "quality/conformity.h"

#include "core/errors.h"

#include <gtest/gtest.h>

#include <algorithm>

#include <cmath>
#include <map>
#include <random>
#include <string>
#include <utility>

namespace tissuemesh {
namespace {

using Eigen::Vector3d;
using Pair = std::pair<int, int>;

void add_oriented_tet(TetMesh& mesh, std::array<int, 4> tet, int tissue) {
  const auto& p = mesh.points;
  if (signed_tet_volume(p[tet[0]], p[tet[1]], p[tet[2]], p[tet[3]]) < 0) {
    std::swap(tet[2], tet[3]);
  }
  mesh.tets.push_back(tet);
  mesh.tissue_ids.push_back(tissue);
}

// nx x ny x nz unit cubes, each cut into 4 corner tets (tissue 1, "fat") and the central tet
// spanned by 4 alternate corners (tissue 2, "gland"). The central tet's edges are diagonals of
// the cube faces. With `alternate`, the central tet takes the corners of even global index sum,
// so that neighbouring cubes cut their common face along the same diagonal (the standard
// conforming 5-tet grid); without it, every cube is cut alike and neighbours' diagonals cross.
TetMesh five_tet_grid(int nx, int ny, int nz, bool alternate) {
  TetMesh mesh;
  mesh.tissue_names = {"fat", "gland"};
  const auto node = [&](int i, int j, int k) { return (k * (ny + 1) + j) * (nx + 1) + i; };
  for (int k = 0; k <= nz; ++k)
    for (int j = 0; j <= ny; ++j)
      for (int i = 0; i <= nx; ++i) mesh.points.emplace_back(i, j, k);

  for (int k = 0; k < nz; ++k) {
    for (int j = 0; j < ny; ++j) {
      for (int i = 0; i < nx; ++i) {
        const int parity = alternate ? (i + j + k) % 2 : 0;
        const auto corner = [&](int c) {  // c = dx + 2 dy + 4 dz
          return node(i + (c & 1), j + (c >> 1 & 1), k + (c >> 2 & 1));
        };
        std::array<int, 4> central;
        int n_central = 0;
        for (int c = 0; c < 8; ++c) {
          const int bits = (c & 1) + (c >> 1 & 1) + (c >> 2 & 1);
          if (bits % 2 == parity) {
            central[n_central++] = corner(c);
          } else {  // a corner tet: this corner and its three neighbours along the cube edges
            add_oriented_tet(mesh, {corner(c), corner(c ^ 1), corner(c ^ 2), corner(c ^ 4)}, 1);
          }
        }
        add_oriented_tet(mesh, central, 2);
      }
    }
  }
  return mesh;
}

TetMesh unit_cube() { return five_tet_grid(1, 1, 1, false); }

void expect_no_defects(const ConformityReport& r) {
  EXPECT_EQ(r.faces_shared_by_more_than_two, 0u);
  EXPECT_EQ(r.duplicate_node_groups, 0u);
  EXPECT_EQ(r.orphan_nodes, 0u);
  EXPECT_EQ(r.inverted_tets, 0u);
  EXPECT_EQ(r.degenerate_tets, 0u);
  EXPECT_EQ(r.nonmanifold_boundary_edges, 0u);
  EXPECT_TRUE(r.defects.empty());
  EXPECT_TRUE(r.conforming());
}

TEST(Conformity, FiveTetCubeIsConformingWithKnownFaceCounts) {
  const ConformityReport r = check_conformity(unit_cube());
  EXPECT_EQ(r.nodes, 8u);
  EXPECT_EQ(r.tets, 5u);
  // Each cube face is cut into 2 triangles, all on corner tets; the central tet touches only
  // corner tets, one per face.
  EXPECT_EQ(r.boundary_faces, 12u);
  const std::map<Pair, std::size_t> expected{{{0, 1}, 12}, {{1, 2}, 4}};
  EXPECT_EQ(r.interface_faces, expected);
  expect_no_defects(r);
}

TEST(Conformity, SwappedNodeOrderGivesOneInvertedTet) {
  TetMesh mesh = unit_cube();
  std::swap(mesh.tets[2][0], mesh.tets[2][1]);
  const ConformityReport r = check_conformity(mesh);
  EXPECT_EQ(r.inverted_tets, 1u);
  EXPECT_EQ(r.degenerate_tets, 0u);
  EXPECT_EQ(r.boundary_faces, 12u);  // faces match by node ids whatever the order
  EXPECT_FALSE(r.conforming());
}

TEST(Conformity, UnusedNodeIsAnOrphan) {
  TetMesh mesh = unit_cube();
  mesh.points.emplace_back(2.0, 2.0, 2.0);
  const ConformityReport r = check_conformity(mesh);
  EXPECT_EQ(r.orphan_nodes, 1u);
  EXPECT_EQ(r.duplicate_node_groups, 0u);
  EXPECT_FALSE(r.conforming());
  ASSERT_EQ(r.defects.size(), 1u);  // located at the node itself
  EXPECT_EQ(r.defects[0].kind, "orphan_nodes");
  EXPECT_EQ(r.defects[0].position, Vector3d(2.0, 2.0, 2.0));
}

// The central tet gets its own copy of corner (0,0,0). Its 3 faces through that corner no longer
// match the corner tets' faces: 6 more boundary faces, 1 interface face left. Every cube-face
// diagonal is now used by 4 boundary triangles, so 6 non-manifold edges: the 3 from (0,0,0) by
// the 2 outer triangles and the 2 corner-tet faces opened through it, the 3 others by the 2 outer
// triangles, one opened corner-tet face and one opened central-tet face. The copy's own edges
// are used by 2 faces each.
TEST(Conformity, DuplicatedNodeCutsTheMeshOpen) {
  TetMesh mesh = unit_cube();
  const int origin = 0, copy = static_cast<int>(mesh.points.size());
  mesh.points.push_back(mesh.points[origin]);
  const std::size_t central = 4;
  ASSERT_EQ(mesh.tissue_ids[central], 2);
  for (int& v : mesh.tets[central]) {
    if (v == origin) v = copy;
  }
  const ConformityReport r = check_conformity(mesh);
  EXPECT_EQ(r.duplicate_node_groups, 1u);
  EXPECT_EQ(r.boundary_faces, 18u);
  EXPECT_EQ(r.interface_faces.at({1, 2}), 1u);
  EXPECT_EQ(r.interface_faces.at({0, 2}), 3u);
  EXPECT_EQ(r.nonmanifold_boundary_edges, 6u);
  EXPECT_EQ(r.orphan_nodes, 0u);
  EXPECT_FALSE(r.conforming());
}

// 400 random nodes, each with a copy displaced by 0.9 (then 1.1) times the coincidence tolerance
// in a random direction. Whatever cells the check bins nodes in, many of these pairs straddle a
// cell border; every near copy must be found and no far one. The nodes stay inside the unit cube
// so that the tolerance stays 1e-9 times its diagonal.
TEST(Conformity, NearlyCoincidentNodesAreFoundWhereverTheyLie) {
  const double tolerance = 1e-9 * std::sqrt(3.0);
  const int pairs = 400;
  for (const auto& [factor, groups] : {std::pair{0.9, pairs}, std::pair{1.1, 0}}) {
    TetMesh mesh = unit_cube();
    std::mt19937 rng(12345);
    std::uniform_real_distribution<double> inside(0.01, 0.99);
    std::normal_distribution<double> gaussian;
    for (int k = 0; k < pairs; ++k) {
      const Vector3d p(inside(rng), inside(rng), inside(rng));
      const Vector3d direction(gaussian(rng), gaussian(rng), gaussian(rng));
      mesh.points.push_back(p);
      mesh.points.push_back(p + factor * tolerance * direction.normalized());
    }
    const ConformityReport r = check_conformity(mesh);
    EXPECT_EQ(r.duplicate_node_groups, static_cast<std::size_t>(groups)) << "factor " << factor;
    EXPECT_EQ(r.orphan_nodes, 2u * pairs);
  }
}

TEST(Conformity, CoincidentNodesFormOneGroupEach) {
  TetMesh mesh = unit_cube();
  for (int copies = 0; copies < 3; ++copies) mesh.points.push_back(mesh.points[0]);
  mesh.points.push_back(mesh.points[7]);
  const ConformityReport r = check_conformity(mesh);
  EXPECT_EQ(r.duplicate_node_groups, 2u);  // {0 and 3 copies}, {7 and 1 copy}
  EXPECT_EQ(r.orphan_nodes, 4u);
}

TEST(Conformity, ThreeTetsOnOneFaceAreCountedOnce) {
  TetMesh mesh;
  mesh.tissue_names = {"fat"};
  mesh.points = {Vector3d(0, 0, 0), Vector3d(1, 0, 0), Vector3d(0, 1, 0), Vector3d(0.2, 0.2, 1),
                 Vector3d(0.2, 0.2, -1), Vector3d(0.3, 0.3, 2)};
  for (int apex : {3, 4, 5}) add_oriented_tet(mesh, {0, 1, 2, apex}, 1);
  const ConformityReport r = check_conformity(mesh);
  EXPECT_EQ(r.faces_shared_by_more_than_two, 1u);
  EXPECT_EQ(r.boundary_faces, 9u);  // the 3 other faces of each tet
  EXPECT_FALSE(r.conforming());
  const auto shared = std::find_if(r.defects.begin(), r.defects.end(), [](const ConformityDefect& d) {
    return d.kind == "faces_shared_by_more_than_two";
  });
  ASSERT_NE(shared, r.defects.end());  // at the centroid of the shared face
  EXPECT_TRUE(shared->position.isApprox(Vector3d(1.0 / 3, 1.0 / 3, 0.0)));
  EXPECT_EQ(shared->tissue, 1);
}

TEST(Conformity, RepeatedNodeAndFlatTetsAreDegenerateNotInverted) {
  TetMesh mesh = unit_cube();
  mesh.tets.push_back({0, 1, 1, 2});        // repeated node
  mesh.tets.push_back({0, 1, 3, 2});        // the 4 corners of the face z = 0: zero volume
  mesh.tissue_ids.insert(mesh.tissue_ids.end(), {1, 1});
  const ConformityReport r = check_conformity(mesh);
  EXPECT_EQ(r.degenerate_tets, 2u);
  EXPECT_EQ(r.inverted_tets, 0u);
  EXPECT_FALSE(r.conforming());
  // Each located at its centroid, in mesh order; the table says where.
  std::vector<Vector3d> where;
  for (const ConformityDefect& d : r.defects)
    if (d.kind == "degenerate_tets") where.push_back(d.position);
  ASSERT_EQ(where.size(), 2u);
  const auto& p = mesh.points;
  EXPECT_TRUE(where[0].isApprox((p[0] + p[1] + p[1] + p[2]) / 4.0));
  EXPECT_TRUE(where[1].isApprox((p[0] + p[1] + p[3] + p[2]) / 4.0));
  const std::string table = format_conformity_table(r, mesh.tissue_names);
  EXPECT_NE(table.find("where (first 10 of each kind; LPS mm):"), std::string::npos) << table;
  EXPECT_EQ(to_json(r)["defects"].size(), r.defects.size());
}

TEST(Conformity, DefectsAreListedAtMostTenOfEachKind) {
  TetMesh mesh = unit_cube();
  for (int i = 0; i < 25; ++i) mesh.points.emplace_back(3.0 + i, 0.0, 0.0);
  const ConformityReport r = check_conformity(mesh);
  EXPECT_EQ(r.orphan_nodes, 25u);
  ASSERT_EQ(r.defects.size(), kMaxDefectsPerKind);
  EXPECT_EQ(r.defects.back().position, Vector3d(3.0 + 9, 0.0, 0.0));
}

TEST(Conformity, NeighbourCubesConformOnlyWhenTheirFaceDiagonalsAgree) {
  // Alternating: the common face is interior; 2 x 12 - 2 x 2 boundary faces.
  const ConformityReport good = check_conformity(five_tet_grid(2, 1, 1, true));
  EXPECT_EQ(good.boundary_faces, 20u);
  const std::map<Pair, std::size_t> expected{{{0, 1}, 20}, {{1, 2}, 8}};
  EXPECT_EQ(good.interface_faces, expected);
  expect_no_defects(good);

  // Same cut in both: the 2 + 2 triangles of the common face cross and match nothing, so they
  // are boundary faces; each of the square's 4 edges is used by 4 boundary triangles (the two
  // cubes' outer faces and their unmatched triangles).
  const ConformityReport bad = check_conformity(five_tet_grid(2, 1, 1, false));
  EXPECT_EQ(bad.boundary_faces, 24u);
  EXPECT_EQ(bad.nonmanifold_boundary_edges, 4u);
  EXPECT_EQ(bad.faces_shared_by_more_than_two, 0u);
  EXPECT_EQ(bad.duplicate_node_groups, 0u);
  EXPECT_FALSE(bad.conforming());
}

TEST(Conformity, AlternatingTenCubedGridIsConforming) {
  const int n = 10;
  const ConformityReport r = check_conformity(five_tet_grid(n, n, n, true));
  EXPECT_EQ(r.tets, 5u * n * n * n);
  EXPECT_EQ(r.boundary_faces, 12u * n * n);  // 6 sides of n^2 squares, 2 triangles each
  const std::map<Pair, std::size_t> expected{{{0, 1}, 12u * n * n}, {{1, 2}, 4u * n * n * n}};
  EXPECT_EQ(r.interface_faces, expected);
  expect_no_defects(r);
}

TEST(Conformity, RejectsInconsistentMeshesAndNonFiniteCoordinates) {
  TetMesh mesh = unit_cube();
  mesh.tets[0][3] = 99;
  EXPECT_THROW(check_conformity(mesh), InputError);
  mesh = unit_cube();
  mesh.points[3].y() = std::nan("");
  EXPECT_THROW(check_conformity(mesh), InputError);
}

TEST(Conformity, JsonNamesTissuePairsAndRoundTrips) {
  TetMesh mesh = unit_cube();
  mesh.points.emplace_back(5.0, 5.0, 5.0);
  const ConformityReport r = check_conformity(mesh);
  const nlohmann::json j = nlohmann::json::parse(to_json(r).dump());
  for (const char* key : {"conforming", "nodes", "tets", "faces_shared_by_more_than_two",
                          "boundary_faces", "duplicate_node_groups", "orphan_nodes",
                          "inverted_tets", "degenerate_tets", "nonmanifold_boundary_edges",
                          "interface_faces"}) {
    EXPECT_TRUE(j.contains(key)) << key;
  }
  EXPECT_EQ(j["conforming"], false);
  EXPECT_EQ(j["orphan_nodes"], 1);
  EXPECT_EQ(j["boundary_faces"], 12);
  ASSERT_EQ(j["interface_faces"].size(), 2u);
  EXPECT_EQ(j["interface_faces"][0]["tissue_a"], "outside");
  EXPECT_EQ(j["interface_faces"][0]["tissue_b"], "fat");
  EXPECT_EQ(j["interface_faces"][0]["tissue_a_id"], 0);
  EXPECT_EQ(j["interface_faces"][0]["faces"], 12);
  EXPECT_EQ(j["interface_faces"][1]["tissue_a"], "fat");
  EXPECT_EQ(j["interface_faces"][1]["tissue_b"], "gland");
  EXPECT_EQ(j["interface_faces"][1]["faces"], 4);
}

TEST(Conformity, TableShowsVerdictsAndNamedInterfaces) {
  TetMesh mesh = unit_cube();
  const std::string ok = format_conformity_table(check_conformity(mesh), mesh.tissue_names);
  EXPECT_NE(ok.find("conforming: yes"), std::string::npos) << ok;
  EXPECT_NE(ok.find("outside"), std::string::npos) << ok;
  EXPECT_NE(ok.find("gland"), std::string::npos) << ok;
  EXPECT_EQ(ok.find("FAIL"), std::string::npos) << ok;

  std::swap(mesh.tets[0][0], mesh.tets[0][1]);
  const std::string bad = format_conformity_table(check_conformity(mesh), mesh.tissue_names);
  EXPECT_NE(bad.find("conforming: NO"), std::string::npos) << bad;
  EXPECT_NE(bad.find("FAIL"), std::string::npos) << bad;
}

}  // namespace
}  // namespace tissuemesh
