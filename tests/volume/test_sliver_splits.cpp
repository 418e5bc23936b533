// Edge splits against slivers (volume/sliver_splits.h) on a Kuhn-split box whose interior nodes
// are pushed towards their neighbours' planes: the smallest dihedral angle rises, every tet stays
// positive, the mesh stays conforming with the same boundary, and every tissue keeps its volume.
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
  const SliverSplitResult r = split_slivers(m, 10.0, 4);
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

}  // namespace
}  // namespace tissuemesh
