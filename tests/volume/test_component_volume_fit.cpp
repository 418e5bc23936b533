// Small enclosed components scaled to their voxel volume: FGT islands of 3-5 voxels across in fat
// come out of Mesh_3 tens of percent too small; after the fit each tissue's volume is within 1 %
// of its voxel volume, fat gives up exactly what the islands gain, no tet is inverted, and no
// moved tet goes below 10 degrees (or below its angle before).
#include "quality/conformity.h"
#include "quality/mesh_quality.h"
#include "support/meshable_volume.h"
#include "volume/direct_mesher.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace tissuemesh;

namespace {

// 40^3 voxels of 1 mm: fat (1) with eight FGT (2) balls of radius 1.5-2.5 voxels, away from the
// border and from each other.
LabelImage islands() {
  LabelImage img;
  img.dims = {40, 40, 40};
  img.spacing = {1, 1, 1};
  img.labels.assign(img.voxel_count(), 1);
  int n = 0;
  for (int a : {12, 27})
    for (int b : {12, 27})
      for (int c : {12, 27}) {
        const double r = 1.5 + 0.15 * n++;
        for (int k = 0; k < 40; ++k)
          for (int j = 0; j < 40; ++j)
            for (int i = 0; i < 40; ++i)
              if ((i - a) * (i - a) + (j - b) * (j - b) + (k - c) * (k - c) <= r * r) img.labels[img.index(i, j, k)] = 2;
      }
  return img;
}

struct Meshed {
  DirectMeshResult result;
  QualityReport quality;
};

Meshed mesh(double fit_below_mm3) {
  DirectMeshParams p;
  p.facet_size_mm = 3;
  p.cell_size_mm = 4;
  p.facet_distance_mm = 0.5;
  p.refine_tissue = "";
  p.smooth_boundaries = false;
  p.fit_island_volumes_below_mm3 = fit_below_mm3;
  p.restore_volumes = false;  // the fit alone
  Progress quiet;
  Meshed r{mesh_labels_direct(islands(), {"fat", "fgt"}, p, quiet), {}};
  r.quality = compute_quality(r.result.mesh);
  return r;
}

double reference(int id) { return test::meshable_volume_mm3(islands(), id); }

}  // namespace

TEST(ComponentVolumeFit, IslandsMatchTheirVoxelVolumeAndFatPaysForIt) {
  const Meshed off = mesh(0), on = mesh(100);
  const double fgt = reference(2);
  EXPECT_LT(off.quality.tissues[1].volume_mm3 / fgt, 0.95) << "without the fit the islands are visibly too small";
  EXPECT_EQ(on.result.island_fit.fitted, 8u);
  EXPECT_EQ(on.result.island_fit.blocked + on.result.island_fit.not_enclosed, 0u);
  EXPECT_NEAR(on.quality.tissues[1].volume_mm3 / fgt, 1.0, 0.01);
  EXPECT_NEAR(on.quality.tissues[0].volume_mm3 / reference(1), 1.0, 0.01);
  // Same tets, same connectivity: the total volume does not change.
  EXPECT_EQ(on.result.mesh.tets, off.result.mesh.tets);
  EXPECT_NEAR(on.quality.total.volume_mm3, off.quality.total.volume_mm3, 1e-6 * off.quality.total.volume_mm3);
  EXPECT_NEAR(on.result.island_fit.volume_moved_mm3,
              on.quality.tissues[1].volume_mm3 - off.quality.tissues[1].volume_mm3, 1e-6 * fgt);
  EXPECT_TRUE(check_conformity(on.result.mesh).conforming());
  EXPECT_GE(on.quality.total.min_dihedral_deg, std::min(10.0, off.quality.total.min_dihedral_deg) - 1e-9);
}
