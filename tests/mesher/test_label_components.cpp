#include "mesher/label_components.h"

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
