#include "image/label_components.h"
#include "image/small_islands.h"

#include <gtest/gtest.h>

using namespace tissuemesh;

TEST(LabelComponents, SixConnectivityAndTissueGrouping) {
  LabelImage img;
  img.dims = {5, 3, 1};
  img.spacing = {1, 1, 1};
  // Row 0: tissue 2 at x=0 and x=2 are separate (x=1 is 0); tissue 1 block on rows 1-2.
  // A diagonal touch (x=4,y=0) with (x=3,y=1) of the same tissue is NOT 6-connected.
  img.labels = {2, 0, 2, 0, 1,
                1, 1, 0, 1, 0,
                1, 1, 0, 1, 0};
  const ComponentMap m = find_components(img);
  ASSERT_EQ(m.components.size(), 5u);
  // Grouped by tissue id: three tissue-1 components first, then the two tissue-2 ones.
  EXPECT_EQ(m.components[0].tissue_id, 1);
  EXPECT_EQ(m.components[2].tissue_id, 1);
  EXPECT_EQ(m.components[3].tissue_id, 2);
  std::size_t total = 0;
  for (const auto& c : m.components) total += c.voxels;
  EXPECT_EQ(total, 9u);
  EXPECT_EQ(m.component_of_voxel[1], -1);
  EXPECT_EQ(m.component_of_voxel[5], m.component_of_voxel[11]);  // (0,1) and (1,2) connected
  EXPECT_NE(m.component_of_voxel[4], m.component_of_voxel[8]);   // diagonal only
  // Every voxel's component has its tissue and contains it in its box.
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 5; ++i) {
      const int c = m.component_of_voxel[img.index(i, j, 0)];
      if (c < 0) continue;
      EXPECT_EQ(m.components[c].tissue_id, img.at(i, j, 0));
      EXPECT_GE(i, m.components[c].box_min[0]);
      EXPECT_LE(i, m.components[c].box_max[0]);
    }
}

TEST(LabelComponents, CentroidIsPhysical) {
  LabelImage img;
  img.dims = {3, 1, 1};
  img.spacing = {2, 1, 1};
  img.origin = {10, 0, 0};
  img.direction = Eigen::Vector3d(-1, -1, 1).asDiagonal();
  img.labels = {1, 1, 0};
  const ComponentMap m = find_components(img);
  ASSERT_EQ(m.components.size(), 1u);
  EXPECT_DOUBLE_EQ(m.components[0].centroid_mm[0], 10 - 1.0);  // voxel centres at x = 10 and 8
}

// Sub-resolution islands (image/small_islands.h).
namespace {

LabelImage block_of(int id, int n) {
  LabelImage img;
  img.dims = {n, n, n};
  img.spacing = {1, 1, 1};
  img.labels.assign(static_cast<std::size_t>(n) * n * n, id);
  return img;
}

void fill(LabelImage& img, int id, int i0, int i1, int j0, int j1, int k0, int k1) {
  for (int k = k0; k < k1; ++k)
    for (int j = j0; j < j1; ++j)
      for (int i = i0; i < i1; ++i) img.labels[img.index(i, j, k)] = id;
}

}  // namespace

TEST(SmallIslands, IslandsUnderTheThresholdTakeTheirSurroundingsLargerOnesStay) {
  LabelImage img = block_of(2, 14);
  fill(img, 1, 2, 3, 2, 3, 2, 3);      // one voxel of tissue 1
  fill(img, 1, 7, 11, 7, 11, 7, 11);   // 64 voxels of tissue 1
  fill(img, 3, 2, 5, 8, 11, 2, 5);     // 26 voxels of tissue 3 ...
  fill(img, 1, 3, 4, 9, 10, 3, 4);     // ... around one of tissue 1: both go, the inner one too
  fill(img, 3, 10, 14, 1, 5, 1, 5);    // tissue 3's largest component (64 voxels)
  const LabelImage before = img;
  const IslandAbsorption r = absorb_small_islands(img, 30);
  EXPECT_EQ(r.voxels, 28u);  // 1 + 26 + 1; the 64-voxel islands stay
  EXPECT_GE(r.islands, 3u);
  std::size_t changed_to_2 = 0;
  for (std::size_t v = 0; v < img.labels.size(); ++v) {
    if (before.labels[v] != img.labels[v]) {
      EXPECT_EQ(img.labels[v], 2) << "voxel " << v;
      ++changed_to_2;
    }
  }
  EXPECT_EQ(changed_to_2, 28u);
  EXPECT_EQ(img.at(8, 8, 8), 1);  // the large island
  // Threshold 1 keeps everything; a second pass finds nothing left.
  LabelImage keep = before;
  EXPECT_EQ(absorb_small_islands(keep, 1).islands, 0u);
  EXPECT_EQ(keep.labels, before.labels);
  EXPECT_EQ(absorb_small_islands(img, 30).islands, 0u);
}

TEST(SmallIslands, WhatWentIsCountedPerTissueAgainstTheInput) {
  // As above, at 0.5 mm: tissue 1 loses two components (the lone voxel and the one inside the
  // tissue-3 shell), tissue 3 its shell; all of it ends as tissue 2.
  LabelImage img = block_of(2, 14);
  img.spacing = {0.5, 0.5, 0.5};
  fill(img, 1, 2, 3, 2, 3, 2, 3);
  fill(img, 1, 7, 11, 7, 11, 7, 11);
  fill(img, 3, 2, 5, 8, 11, 2, 5);
  fill(img, 1, 3, 4, 9, 10, 3, 4);
  fill(img, 3, 10, 14, 1, 5, 1, 5);
  const IslandAbsorption r = absorb_small_islands(img, 30);
  EXPECT_EQ(r.min_voxels, 30u);
  EXPECT_TRUE(r.kept_whole.empty());
  EXPECT_EQ(r.islands, 3u);
  EXPECT_EQ(r.voxels, 28u);
  EXPECT_DOUBLE_EQ(r.volume_mm3, 28 * 0.125);
  ASSERT_EQ(r.tissues.size(), 2u);
  EXPECT_EQ(r.tissues[0].tissue_id, 1);
  EXPECT_EQ(r.tissues[0].islands, 2u);
  EXPECT_EQ(r.tissues[0].voxels, 2u);
  EXPECT_EQ(r.tissues[0].voxels_into, (std::map<int, std::size_t>{{2, 2}}));
  EXPECT_EQ(r.tissues[1].tissue_id, 3);
  EXPECT_EQ(r.tissues[1].islands, 1u);
  EXPECT_EQ(r.tissues[1].voxels, 26u);
  EXPECT_DOUBLE_EQ(r.tissues[1].volume_mm3, 26 * 0.125);

  // Adding a later absorption sums tissue by tissue and keeps the order by id.
  IslandAbsorption later;
  later.min_voxels = 30;
  later.islands = later.voxels = 1;
  later.tissues.push_back(TissueIslands{2, 1, 1, 0.125, {{0, 1}}});
  IslandAbsorption sum = r;
  sum.add(later);
  EXPECT_EQ(sum.islands, 4u);
  EXPECT_EQ(sum.voxels, 29u);
  ASSERT_EQ(sum.tissues.size(), 3u);
  EXPECT_EQ(sum.tissues[1].tissue_id, 2);
  EXPECT_EQ(sum.tissues[1].voxels_into.at(0), 1u);
  EXPECT_EQ(sum.tissues[2].tissue_id, 3);
}

TEST(SmallIslands, TheMajorityOfFaceNeighboursWinsAndTheBorderCountsAsOutside) {
  // A one-voxel island of tissue 3 on the plane between tissue 1 (below, k < 5) and tissue 2
  // (k >= 5), sitting in tissue 2: five of its six neighbours are 2, one is 1.
  LabelImage img = block_of(1, 10);
  fill(img, 2, 0, 10, 0, 10, 5, 10);
  fill(img, 3, 4, 5, 4, 5, 5, 6);
  // A one-voxel island of tissue 3 in a corner of the image: three neighbours outside the
  // image (outside, 0), three of tissue 1.
  fill(img, 3, 0, 1, 0, 1, 0, 1);
  fill(img, 3, 7, 9, 7, 9, 1, 3);  // tissue 3's largest component (8 voxels), which stays
  const IslandAbsorption r = absorb_small_islands(img, 2);
  EXPECT_EQ(r.islands, 2u);
  EXPECT_EQ(img.at(4, 4, 5), 2);
  // Tie 3 : 3 between outside and tissue 1: the lower id (outside) wins.
  EXPECT_EQ(img.at(0, 0, 0), 0);
}

TEST(SmallIslands, AnIslandWhoseSmallShellTookItsIdStaysTissue) {
  // A one-voxel tissue-2 island inside a 26-voxel shell of tissue 1, inside tissue 2. The shell
  // (lower id) goes first and becomes tissue 2, so every neighbour of the inner voxel is then of
  // its own tissue: it is part of the surrounding tissue now and must not become outside.
  // Tissue 1's largest component is a slab at i < 2, apart from the shell.
  LabelImage img = block_of(2, 9);
  fill(img, 1, 0, 2, 0, 9, 0, 9);
  fill(img, 1, 3, 6, 3, 6, 3, 6);
  fill(img, 2, 4, 5, 4, 5, 4, 5);
  absorb_small_islands(img, 30);
  for (int k = 0; k < 9; ++k)
    for (int j = 0; j < 9; ++j)
      for (int i = 2; i < 9; ++i) EXPECT_EQ(img.at(i, j, k), 2) << "voxel " << i << " " << j << " " << k;
}

TEST(SmallIslands, ATissueIsNeverRemovedWhole) {
  // A marker clip: tissue 3 is two components of 8 and 1 voxels inside tissue 2, tissue 1 a lone
  // voxel. At a threshold of 30 every component of 1 and 3 is under it; the largest of each stays
  // (tissue 1's only voxel, tissue 3's 8-voxel cube), the other clip voxel goes, and the kept ones
  // are reported with their sizes.
  LabelImage img = block_of(2, 12);
  fill(img, 3, 2, 4, 2, 4, 2, 4);
  fill(img, 3, 8, 9, 8, 9, 8, 9);
  fill(img, 1, 6, 7, 2, 3, 2, 3);
  const LabelImage before = img;
  const IslandAbsorption r = absorb_small_islands(img, 30);
  EXPECT_EQ(r.islands, 1u);
  EXPECT_EQ(r.voxels, 1u);
  EXPECT_EQ(img.at(8, 8, 8), 2);
  EXPECT_EQ(img.at(2, 2, 2), 3);
  EXPECT_EQ(img.at(3, 3, 3), 3);
  EXPECT_EQ(img.at(6, 2, 2), 1);
  EXPECT_EQ(r.kept_whole, (std::map<int, std::size_t>{{1, 1}, {3, 8}}));
  // Tissue 2 is far above the threshold: never reported as kept.
  EXPECT_EQ(r.kept_whole.count(2), 0u);
  // Again: nothing left to absorb, the same kept.
  const IslandAbsorption again = absorb_small_islands(img, 30);
  EXPECT_EQ(again.islands, 0u);
  EXPECT_EQ(again.kept_whole, r.kept_whole);
}

TEST(SmallIslands, AHintedAbsorptionFindsWhatAFullOneFinds) {
  // Tissue 1 in tissue 2: a 4 x 4 x 4 block with a one-voxel-thick filament of 5 voxels along x.
  // No islands under 4 voxels to start with.
  LabelImage img = block_of(2, 14);
  fill(img, 1, 1, 5, 1, 5, 1, 5);
  fill(img, 1, 5, 10, 3, 4, 3, 4);
  LabelImage clean = img;
  ASSERT_EQ(absorb_small_islands(clean, 4).islands, 0u);
  // A repair-like change raises the filament's third voxel to 2, the tissue around: the
  // filament's last two voxels become a two-voxel island of tissue 1 that contains no changed
  // voxel (only its face neighbour changed), so the hint's neighbours must find it.
  const std::size_t cut = img.index(7, 3, 3);
  img.labels[cut] = 2;
  LabelImage full = img, hinted = img;
  const std::vector<std::size_t> changed{cut};
  const IslandAbsorption a = absorb_small_islands(full, 4), b = absorb_small_islands(hinted, 4, &changed);
  EXPECT_EQ(a.islands, 1u);
  EXPECT_EQ(b.islands, a.islands);
  EXPECT_EQ(b.voxels, a.voxels);
  EXPECT_EQ(hinted.labels, full.labels);
  EXPECT_EQ(hinted.at(8, 3, 3), 2);  // the cut-off end took its surroundings
  // A change that leaves no island: nothing found, nothing changed, as without the hint.
  LabelImage quiet = clean;
  const std::size_t corner = quiet.index(1, 1, 1);
  quiet.labels[corner] = 2;  // the block's corner voxel joins the surrounding tissue
  const LabelImage quiet_before = quiet;
  const std::vector<std::size_t> corner_changed{corner};
  EXPECT_EQ(absorb_small_islands(quiet, 4, &corner_changed).islands, 0u);
  EXPECT_EQ(quiet.labels, quiet_before.labels);
}
