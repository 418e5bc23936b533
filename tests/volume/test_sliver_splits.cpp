// Edge splits against slivers (volume/sliver_splits.h) on a Kuhn-split box whose interior nodes
// are pushed towards their neighbours' planes: the smallest dihedral angle rises, every tet stays
// positive, the mesh stays conforming with the same boundary, and every tissue keeps its volume.
// And on a sliver no split inside one tissue reaches (from a fragmented-breast mesh: an FGT tet
// of 7.7 degrees with two faces on fat, one on a vessel, one on FGT): given to fat first, it goes,
// moving its own volume and nothing else.
#include "volume/sliver_splits.h"

#include "quality/conformity.h"
#include "quality/mesh_quality.h"
#include "support/complex_meshes.h"
#include "support/model_fixture.h"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

namespace tissuemesh {
namespace {

TetMesh flattened_box() {
  TetMesh m = test::box_mesh({0, 0, 0}, {8, 8, 8}, 4, 4, 4);
  // Two tissues by x (the interface x = 4 stays flat and is never split across).
  for (std::size_t t = 0; t < m.tets.size(); ++t) {
    double x = 0;
    for (int v : m.tets[t]) x += 0.25 * m.points[v].x();
    m.tissue_ids[t] = x < 4 ? 1 : 2;
  }
  m.tissue_names = {"left", "right"};
  // Interior nodes off the interface slide along a diagonal: flat tets appear around them.
  for (Eigen::Vector3d& p : m.points) {
    const bool interior = p.minCoeff() > 0 && p.maxCoeff() < 8 && p.x() != 4;
    if (interior) p += 0.9 * Eigen::Vector3d(0.9, 0.9, -0.9);
  }
  return m;
}

TEST(SliverSplits, RaiseTheWorstAngleAndKeepVolumesAndBoundary) {
  TetMesh m = flattened_box();
  const QualityReport before = compute_quality(m);
  ASSERT_GT(before.total.tets_below_10deg, 0u);
  const std::vector<double> volumes_before = test::tissue_volumes(m);
  const SliverSplitResult r = split_slivers(m, 10.0, false, 4);
  const QualityReport after = compute_quality(m);
  std::cout << "[ volume   ] splits: " << r.splits << "; min dihedral " << before.total.min_dihedral_deg << " -> "
            << after.total.min_dihedral_deg << " deg, tets below 10 deg " << before.total.tets_below_10deg << " -> "
            << after.total.tets_below_10deg << "\n";
  EXPECT_GT(r.splits, 0u);
  EXPECT_GT(after.total.min_dihedral_deg, before.total.min_dihedral_deg);
  EXPECT_LT(after.total.tets_below_10deg, before.total.tets_below_10deg);
  const ConformityReport c = check_conformity(m);
  EXPECT_TRUE(c.conforming());
  EXPECT_EQ(c.inverted_tets, 0u);
  const std::vector<double> volumes_after = test::tissue_volumes(m);
  for (std::size_t t = 1; t < volumes_before.size(); ++t)
    EXPECT_NEAR(volumes_after[t], volumes_before[t], 1e-9 * volumes_before[t]) << t;
  EXPECT_EQ(m.points.size(), test::box_mesh({0, 0, 0}, {8, 8, 8}, 4, 4, 4).points.size() + r.splits);
}

namespace sliver_patch {
// Nodes [mm] and tets (four nodes, tissue) of the tets around the four nodes of the sliver.
const double kNodes[][3] = {
    {0.926238, 0.163355, -0.630896}, {0.062130, 0.758880, -1.158223},
    {0.343276, 1.240240, -0.536320}, {-2.235714, -0.281418, -1.104090},
    {-0.298594, -0.885150, 0.660351}, {-0.117019, 0.226500, 0.921834},
    {-0.868046, -0.033249, 0.480004}, {-0.188149, 0.810396, 0.965102},
    {-0.623434, 0.595074, 0.630393}, {1.016971, -1.086143, 0.008823},
    {0.742938, -0.051099, 0.821154}, {-0.939482, 1.488976, -0.467487},
    {0.540320, -0.837804, 0.643400}, {2.173310, -0.160765, 0.055258},
    {-0.177196, 1.477468, 0.837148}, {-0.924002, -1.659430, -0.989844},
    {0.255541, -1.077099, -1.066565}, {-0.166132, 0.642361, 0.114758},
    {0.341053, 0.864011, 0.710276}, {-0.410615, 0.015335, -0.032985},
    {-1.310424, -0.907839, -1.446389}, {0.978179, -0.308751, 0.117006},
    {0.565595, 0.152847, 0.248776}, {0.201841, -0.299062, -0.004448},
    {0.111416, -0.847631, 0.222966},
};
const int kTets[][5] = {
    {7, 17, 5, 8, 6}, {11, 19, 8, 6, 1}, {14, 17, 18, 7, 6}, {5, 22, 17, 18, 6},
    {17, 19, 5, 8, 2}, {1, 16, 23, 19, 1}, {0, 18, 22, 13, 2}, {12, 23, 5, 10, 6},
    {0, 22, 21, 13, 2}, {18, 17, 5, 7, 6}, {16, 15, 24, 19, 1}, {22, 23, 21, 10, 6},
    {1, 11, 3, 19, 1}, {19, 17, 11, 8, 1}, {8, 19, 5, 6, 2}, {14, 17, 7, 8, 6},
    {23, 21, 9, 0, 1}, {5, 23, 22, 10, 6}, {23, 16, 24, 19, 1}, {23, 24, 4, 19, 2},
    {17, 23, 22, 19, 2}, {19, 23, 22, 5, 2}, {23, 4, 5, 19, 2}, {17, 19, 22, 5, 6},
    {1, 11, 17, 2, 1}, {24, 15, 4, 19, 1}, {11, 1, 17, 19, 1}, {0, 1, 17, 2, 1},
    {21, 24, 12, 23, 6}, {21, 9, 24, 23, 1}, {19, 11, 3, 6, 1}, {19, 4, 5, 6, 2},
    {19, 15, 4, 6, 1}, {12, 21, 23, 10, 6}, {18, 5, 22, 10, 6}, {23, 22, 21, 0, 1},
    {17, 14, 18, 2, 2}, {16, 1, 23, 0, 1}, {13, 18, 22, 10, 2}, {23, 9, 24, 16, 1},
    {11, 14, 17, 2, 1}, {1, 20, 16, 19, 1}, {16, 20, 15, 19, 1}, {23, 17, 22, 0, 1},
    {13, 22, 21, 10, 2}, {16, 23, 9, 0, 1}, {14, 17, 8, 11, 1}, {1, 3, 20, 19, 1},
    {23, 1, 19, 17, 1}, {23, 1, 17, 0, 1}, {18, 0, 22, 17, 2}, {18, 0, 17, 2, 2},
    {19, 3, 20, 15, 1}, {19, 3, 15, 6, 1}, {23, 4, 24, 12, 2}, {23, 4, 12, 5, 2},
};
}  // namespace sliver_patch

TetMesh three_interface_sliver() {
  TetMesh m;
  for (const auto& p : sliver_patch::kNodes) m.points.emplace_back(p[0], p[1], p[2]);
  for (const auto& t : sliver_patch::kTets) {
    m.tets.push_back({t[0], t[1], t[2], t[3]});
    m.tissue_ids.push_back(t[4]);
  }
  m.tissue_names = {"fat", "fgt", "tumor", "skin", "muscle", "vessel"};
  return m;
}

TEST(SliverSplits, GiveAFlatInterfaceWedgeToTheTissueAroundItsEdge) {
  const TetMesh input = three_interface_sliver();
  const QualityReport before = compute_quality(input);
  ASSERT_LT(before.total.min_dihedral_deg, 8.0);
  ASSERT_EQ(before.total.tets_below_10deg, 1u);
  const ConformityReport conformity_before = check_conformity(input);

  TetMesh kept = input;  // without relabels no edge of the sliver is inside one tissue
  EXPECT_EQ(split_slivers(kept, 10.0, false).splits, 0u);

  TetMesh m = input;
  const SliverSplitResult r = split_slivers(m, 10.0, true);
  const QualityReport after = compute_quality(m);
  std::cout << "[ volume   ] min dihedral " << before.total.min_dihedral_deg << " -> " << after.total.min_dihedral_deg
            << " deg; " << r.relabelled_wedges << " wedge of " << r.volume_relabelled_mm3 << " mm^3 relabelled\n";
  EXPECT_EQ(r.splits, 1u);
  EXPECT_EQ(r.relabelled_wedges, 1u);
  EXPECT_GE(after.total.min_dihedral_deg, 10.0);
  EXPECT_EQ(after.total.tets_below_10deg, 0u);
  const ConformityReport c = check_conformity(m);
  EXPECT_EQ(c.inverted_tets, 0u);
  EXPECT_EQ(c.degenerate_tets, conformity_before.degenerate_tets);
  EXPECT_EQ(c.nonmanifold_boundary_edges, conformity_before.nonmanifold_boundary_edges);
  // The sliver's volume moved from FGT (2) to fat (1); the vessel (6) and the total kept theirs.
  const std::vector<double> v0 = test::tissue_volumes(input), v1 = test::tissue_volumes(m);
  EXPECT_GT(r.volume_relabelled_mm3, 0.0);
  EXPECT_NEAR(v1[1] - v0[1], r.volume_relabelled_mm3, 1e-12);
  EXPECT_NEAR(v1[2] - v0[2], -r.volume_relabelled_mm3, 1e-12);
  EXPECT_NEAR(v1[6], v0[6], 1e-12);
}

}  // namespace
}  // namespace tissuemesh
