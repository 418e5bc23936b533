// Local thickness against shapes whose thickness is known: slabs of n voxels (n h for odd n,
// (n - 1) h for even n, as the header documents), a ball (its diameter at the centre), and thick
// regions above the cap (+infinity).
#include "image/local_thickness.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace tissuemesh;

namespace {

// Label 1 everywhere, label 2 in the slab x in [x0, x0 + n).
LabelImage slab(int n, double h) {
  LabelImage img;
  img.dims = {40, 12, 12};
  img.spacing = {h, h, h};
  img.labels.assign(img.voxel_count(), 1);
  for (int k = 0; k < 12; ++k)
    for (int j = 0; j < 12; ++j)
      for (int i = 10; i < 10 + n; ++i) img.labels[img.index(i, j, k)] = 2;
  return img;
}

}  // namespace

TEST(LocalThickness, SlabsOfOddAndEvenVoxelCounts) {
  for (int n : {1, 2, 3, 4, 5, 7}) {
    const double h = 0.5;
    const LabelImage img = slab(n, h);
    const auto t = local_thickness(img, 20.0);
    const double expected = (n % 2 == 1 ? n : n - 1) * h;
    for (int i = 10; i < 10 + n; ++i)
      EXPECT_NEAR(t[img.index(i, 6, 6)], expected, 1e-5) << "slab of " << n << " voxels, voxel " << i;
  }
}

TEST(LocalThicknessCap, ThickRegionsAreInfiniteThinOnesNot) {
  const LabelImage img = slab(3, 1.0);
  // The fat on either side of the slab is 10 and 27 voxels thick (bounded by the image border).
  const auto capped = local_thickness(img, 5.0);
  EXPECT_TRUE(std::isinf(capped[img.index(30, 6, 6)]));
  EXPECT_NEAR(capped[img.index(11, 6, 6)], 3.0, 1e-5);
  // Across the 12-voxel image in y and z even the wide fat is at most 12 voxels thick: a large cap
  // gives finite values bounded by that.
  const auto wide = local_thickness(img, 100.0);
  EXPECT_LE(wide[img.index(30, 6, 6)], 12.0 + 1e-5);
  EXPECT_GE(wide[img.index(30, 6, 6)], 9.0);
}

TEST(LocalThickness, BallDiameterAtItsCentre) {
  LabelImage img;
  const int n = 31;
  img.dims = {n, n, n};
  img.spacing = {0.25, 0.25, 0.25};
  img.labels.assign(img.voxel_count(), 1);
  const double r = 9.0;  // voxels
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
        if (std::pow(i - 15, 2) + std::pow(j - 15, 2) + std::pow(k - 15, 2) <= r * r) img.labels[img.index(i, j, k)] = 2;
  const auto t = local_thickness(img, 100.0);
  // Diameter of the voxel ball: 19 voxels across the centre line = 4.75 mm. Measured to the
  // centres of the boundary voxels, whose layer is ragged on a voxel sphere, it comes out at most
  // two voxels less (conservative: finer elements), never more.
  for (int k : {15, 7}) {  // the centre, and near the rim: it lies in the same largest ball
    EXPECT_LE(t[img.index(15, 15, k)], 19 * 0.25 + 1e-6);
    EXPECT_GE(t[img.index(15, 15, k)], 19 * 0.25 - 2 * 0.25);
  }
}
