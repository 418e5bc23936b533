// The direct pipeline with a tet budget (direct.target_tets): the count lands within 10 % of the
// budget at two budgets a factor three apart, every tissue keeps its volume, and budgets the image
// cannot meet (below what its parts need, above what its voxels give) are input errors that say
// which way to move the budget.
#include "core/errors.h"
#include "quality/conformity.h"
#include "quality/mesh_quality.h"
#include "volume/direct_mesher.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

using namespace tissuemesh;

namespace {

// 48^3 voxels of 1 mm: fat (1), a ball of FGT (2) of radius 9 mm, a 3-voxel skin (3) on the
// faces x = 0..2, outside (0) nowhere: every tissue touches the image border.
LabelImage body() {
  LabelImage img;
  img.dims = {48, 48, 48};
  img.spacing = {1, 1, 1};
  img.labels.assign(img.voxel_count(), 1);
  for (int k = 0; k < 48; ++k)
    for (int j = 0; j < 48; ++j)
      for (int i = 0; i < 48; ++i) {
        if (i < 3) img.labels[img.index(i, j, k)] = 3;
        else if (std::pow(i - 26, 2) + std::pow(j - 24, 2) + std::pow(k - 24, 2) <= 81) img.labels[img.index(i, j, k)] = 2;
      }
  return img;
}

DirectMeshParams budget(std::size_t target) {
  DirectMeshParams p;
  p.target_tets = target;
  p.refine_tissue = "";
  return p;
}

const std::vector<std::string> kNames = {"fat", "fgt", "skin"};

}  // namespace

TEST(DirectBudget, CountWithinTenPercentAtTwoBudgets) {
  const LabelImage img = body();
  for (std::size_t target : {20000u, 60000u}) {
    Progress quiet;
    const DirectMeshResult r = mesh_labels_direct(img, kNames, budget(target), quiet);
    const double n = static_cast<double>(r.mesh.tets.size());
    EXPECT_NEAR(n / static_cast<double>(target), 1.0, 0.10) << "budget " << target;
    ASSERT_FALSE(r.sizing.attempts.empty());
    EXPECT_LE(r.sizing.attempts.size(), 4u);
    EXPECT_TRUE(check_conformity(r.mesh).conforming());
    // Volumes: the skin is 3 voxels thick and cut by the image border; sizes that keep it and
    // the volume restoration give every tissue its voxel volume.
    ASSERT_TRUE(r.restoration);
    const QualityReport q = compute_quality(r.mesh);
    for (std::size_t t = 0; t < q.tissues.size(); ++t) {  // in tissue id order
      const double voxels = static_cast<double>(std::count(img.labels.begin(), img.labels.end(), t + 1)) * img.voxel_volume();
      EXPECT_NEAR(q.tissues[t].volume_mm3 / voxels, 1.0, 0.01) << q.tissues[t].name << " at budget " << target;
    }
  }
}

TEST(DirectBudget, TooSmallABudgetIsAnInputErrorThatNamesALargerOne) {
  Progress quiet;
  try {
    mesh_labels_direct(body(), kNames, budget(300), quiet);
    FAIL() << "a budget of 300 tets cannot hold a 3-voxel skin on a 48 mm face";
  } catch (const InputError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("direct.target_tets"), std::string::npos) << m;
    EXPECT_NE(m.find("raise direct.target_tets to at least"), std::string::npos) << m;
  }
}

TEST(DirectBudget, TooLargeABudgetIsAnInputErrorThatNamesASmallerOne) {
  Progress quiet;
  DirectMeshParams p = budget(50000000);
  p.min_edge_mm = 2.0;  // keeps the finest attempt small: at most a few 100 000 tets
  try {
    mesh_labels_direct(body(), kNames, p, quiet);
    FAIL() << "2 mm edges cannot give 50 M tets in 110 cm^3";
  } catch (const InputError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("lower direct.target_tets to at most"), std::string::npos) << m;
  }
}
