// The budget solve of image_sizing: the prediction falls as the largest edge grows, the solved edge
// meets the target, grading bounds the growth of the field, and a budget the thin parts alone
// exceed coarsens them and names their tissue.
#include "image/local_thickness.h"
#include "volume/image_sizing.h"
#include "core/errors.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace tissuemesh;

namespace {

// Fat (1) in a 40 x 40 x 40 image of 1 mm voxels with a 2-voxel skin (2) at x in [0, 2).
LabelImage skin_on_fat() {
  LabelImage img;
  img.dims = {40, 40, 40};
  img.spacing = {1, 1, 1};
  img.labels.assign(img.voxel_count(), 1);
  for (int k = 0; k < 40; ++k)
    for (int j = 0; j < 40; ++j)
      for (int i = 0; i < 2; ++i) img.labels[img.index(i, j, k)] = 2;
  return img;
}

// The budgets below are chosen for this factor (mean tet volume / edge^3), not the default.
constexpr double kFactor = 0.035;

ImageSizing size(const LabelImage& img, std::size_t target) {
  ImageSizingParams p;
  p.target_tets = target;
  p.min_edge_mm = 1.0;
  p.max_edge_mm = 10.0;
  p.tet_volume_factor = kFactor;
  const auto t = local_thickness(img, p.max_edge_mm);
  return size_from_image(img, t, [](int, int, int) { return 1e9; }, {"fat", "skin"}, p);
}

}  // namespace

TEST(ImageSizing, SolvedEdgeMeetsTheTargetAndPredictionFalls) {
  const LabelImage img = skin_on_fat();
  const ImageSizing s = size(img, 200000);
  EXPECT_EQ(s.thickness_scale, 1.0);
  EXPECT_NEAR(s.predicted_tets, 200000.0, 200.0);
  const double f = kFactor;
  double last = 1e300;
  for (double e = 1.0; e <= 10.0; e += 0.5) {
    const double n = s.predict(e, f);
    EXPECT_LE(n, last + 1e-9);
    last = n;
  }
  // Near the skin the edge is its thickness (1 mm for an even 2-voxel layer); it grows away from it
  // by at most the growth rate (with the 8 % of the chamfer distance).
  EXPECT_NEAR(s.edge_at(0.5, 20, 20), 1.0, 1e-6);
  for (int x = 2; x < 40; ++x) EXPECT_LE(s.edge_at(x, 20, 20), 1.0 + 0.3 * 1.08 * x + 1e-6);
  EXPECT_LE(s.edge_at(39, 20, 20), s.global_edge_mm + 1e-9);
  EXPECT_TRUE(s.coarsened.empty());
}

TEST(ImageSizing, BudgetBelowTheThinPartsCoarsensThemAndNamesTheTissue) {
  const LabelImage img = skin_on_fat();
  const ImageSizing s = size(img, 2500);
  EXPECT_GT(s.thickness_scale, 1.0);
  EXPECT_NEAR(s.predicted_tets, 2500.0, 250.0);
  ASSERT_FALSE(s.coarsened.empty());
  EXPECT_EQ(s.coarsened[0].tissue, "skin");
  EXPECT_NEAR(s.coarsened[0].thin_volume_mm3, 2.0 * 40 * 40, 1e-6);
}

TEST(ImageSizing, RejectsAZeroBudget) {
  const LabelImage img = skin_on_fat();
  EXPECT_THROW(size(img, 0), InputError);
}
