// The direct pipeline on a fragmented label image: components under the size threshold join their
// surroundings and are reported by tissue, count and volume; the kept ones are meshed; the seed
// count does not grow with the number of absorbed islands.
#include "quality/conformity.h"
#include "quality/mesh_quality.h"
#include "support/tolerances.h"
#include "volume/direct_mesher.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

using namespace tissuemesh;

namespace {

constexpr int kN = 24;            // image side, voxels of 1 mm
constexpr int kBlockVoxels = 64;  // each large island: 4 x 4 x 4 voxels

// Fat (1) filling the image, three 4 x 4 x 4 FGT (2) blocks, and `singles` one-voxel FGT islands
// on a lattice of pitch 2 that keeps clear of the blocks (no two islands touch).
LabelImage fragmented(int singles) {
  LabelImage img;
  img.dims = {kN, kN, kN};
  img.spacing = {1, 1, 1};
  img.labels.assign(img.voxel_count(), 1);
  const int corners[3][3] = {{3, 3, 3}, {15, 5, 9}, {7, 15, 16}};
  auto near_block = [&](int i, int j, int k) {
    for (const auto& c : corners)
      if (i >= c[0] - 1 && i <= c[0] + 4 && j >= c[1] - 1 && j <= c[1] + 4 && k >= c[2] - 1 && k <= c[2] + 4)
        return true;
    return false;
  };
  for (const auto& c : corners)
    for (int k = 0; k < 4; ++k)
      for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 4; ++i) img.labels[img.index(c[0] + i, c[1] + j, c[2] + k)] = 2;
  int placed = 0;
  for (int k = 1; k < kN - 1 && placed < singles; k += 2)
    for (int j = 1; j < kN - 1 && placed < singles; j += 2)
      for (int i = 1; i < kN - 1 && placed < singles; i += 2)
        if (!near_block(i, j, k)) {
          img.labels[img.index(i, j, k)] = 2;
          ++placed;
        }
  EXPECT_EQ(placed, singles);
  return img;
}

DirectMeshParams coarse(int min_component_voxels) {
  DirectMeshParams p;
  p.facet_size_mm = 2.0;
  p.facet_distance_mm = 0.3;
  p.cell_size_mm = 3.0;
  p.refine_tissue = "";
  p.min_component_voxels = min_component_voxels;
  p.min_component_mm3 = 0.0;
  return p;
}

std::size_t tets_of(const TetMesh& mesh, int tissue) {
  return static_cast<std::size_t>(std::count(mesh.tissue_ids.begin(), mesh.tissue_ids.end(), tissue));
}

}  // namespace

TEST(DirectIslands, ThresholdFromVoxelsOrVolume) {
  DirectMeshParams p;
  p.min_component_voxels = 0;
  p.min_component_mm3 = 1.0;
  EXPECT_EQ(p.absorb_below_voxels(0.25 * 0.25 * 0.25), 64u);  // a 1 mm cube of 0.25 mm voxels
  EXPECT_EQ(p.absorb_below_voxels(0.125), 8u);
  EXPECT_EQ(p.absorb_below_voxels(1.0), 1u);  // nothing is smaller than one voxel
  p.min_component_voxels = 10;
  EXPECT_EQ(p.absorb_below_voxels(0.125), 10u);  // the larger of the two
  p.min_component_voxels = 0;
  p.min_component_mm3 = 0.0;
  EXPECT_EQ(p.absorb_below_voxels(0.125), 0u);
}

TEST(DirectIslands, SmallComponentsAreAbsorbedAndReportedLargeOnesMeshed) {
  const LabelImage img = fragmented(50);
  Progress progress;
  const DirectMeshResult r = mesh_labels_direct(img, {"fat", "fgt"}, coarse(8), progress);
  EXPECT_EQ(r.image_components, 1u + 3u + 50u);
  EXPECT_EQ(r.meshed_components, 1u + 3u);
  EXPECT_EQ(r.absorbed.min_voxels, 8u);
  EXPECT_EQ(r.absorbed.islands, 50u);
  ASSERT_EQ(r.absorbed.tissues.size(), 1u);
  const TissueIslands& fgt = r.absorbed.tissues[0];
  EXPECT_EQ(fgt.tissue_id, 2);
  EXPECT_EQ(fgt.islands, 50u);
  EXPECT_EQ(fgt.voxels, 50u);
  EXPECT_DOUBLE_EQ(fgt.volume_mm3, 50.0);
  ASSERT_EQ(fgt.voxels_into.size(), 1u);
  EXPECT_EQ(fgt.voxels_into.at(1), 50u);  // into fat
  EXPECT_TRUE(r.missed.empty());

  // Each kept block has FGT tets around its centre.
  const Eigen::Vector3d centres[3] = {{4.5, 4.5, 4.5}, {16.5, 6.5, 10.5}, {8.5, 16.5, 17.5}};
  for (const auto& c : centres) {
    std::size_t near = 0;
    for (std::size_t t = 0; t < r.mesh.tets.size(); ++t) {
      if (r.mesh.tissue_ids[t] != 2) continue;
      Eigen::Vector3d g = Eigen::Vector3d::Zero();
      for (int v : r.mesh.tets[t]) g += r.mesh.points[v] / 4;
      near += (g - c).norm() < 2.5;
    }
    EXPECT_GT(near, 0u) << c.transpose();
  }

  // Volumes: fat fills the image, whose border voxels' outer halves the volume restoration gives
  // back; FGT is the three blocks (the absorbed voxels are fat now), meshed with rounded edges
  // (smoothed labels, facet distance 0.3 mm) and restored to their voxel volume.
  const QualityReport q = compute_quality(r.mesh);
  const double total = std::pow(kN, 3);
  EXPECT_NEAR(q.tissues[0].volume_mm3 + q.tissues[1].volume_mm3, total, 1e-3 * total);
  EXPECT_NEAR(q.tissues[1].volume_mm3, 3.0 * kBlockVoxels, 1e-3 * 3 * kBlockVoxels);
  EXPECT_TRUE(check_conformity(r.mesh).conforming());
}

TEST(DirectIslands, SeedCountDoesNotGrowWithAbsorbedIslands) {
  Progress p1, p2;
  const DirectMeshResult few = mesh_labels_direct(fragmented(50), {"fat", "fgt"}, coarse(8), p1);
  const DirectMeshResult many = mesh_labels_direct(fragmented(500), {"fat", "fgt"}, coarse(8), p2);
  EXPECT_EQ(many.absorbed.islands, 500u);
  EXPECT_EQ(many.meshed_components, few.meshed_components);
  EXPECT_LE(many.initial_points, few.initial_points);
  // At most 9 start voxels with 6 rays each per kept component, however many islands went.
  EXPECT_LE(many.initial_points, 9u * 6u * many.meshed_components);
  EXPECT_GT(tets_of(many.mesh, 2), 0u);
}

TEST(DirectIslands, ThresholdZeroKeepsEveryComponent) {
  const LabelImage img = fragmented(50);
  Progress progress;
  const DirectMeshResult r = mesh_labels_direct(img, {"fat", "fgt"}, coarse(0), progress);
  EXPECT_EQ(r.absorbed.islands, 0u);
  EXPECT_TRUE(r.absorbed.tissues.empty());
  EXPECT_EQ(r.meshed_components, r.image_components);
  EXPECT_EQ(r.meshed_components, 54u);
  // Every one-voxel island is seeded: its tets exist or it is named in `missed`.
  EXPECT_GT(r.initial_points, 50u);
  for (const MissedComponent& m : r.missed) {
    EXPECT_EQ(m.tissue, "fgt");
    EXPECT_EQ(m.voxels, 1u);
  }
  EXPECT_TRUE(check_conformity(r.mesh).conforming());
}

TEST(DirectIslands, ABoundaryToleranceAboveTheVoxelSizeIsAWarning) {
  LabelImage img = fragmented(0);
  img.spacing = {0.1, 0.1, 0.1};  // facet distance 0.3 mm is three voxels
  Progress progress;
  const DirectMeshResult r = mesh_labels_direct(img, {"fat", "fgt"}, coarse(0), progress);
  ASSERT_FALSE(r.warnings.empty());
  EXPECT_NE(r.warnings[0].find("direct.facet_distance_mm"), std::string::npos) << r.warnings[0];
}
