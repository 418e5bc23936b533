// Labels carried through a deformation (workflows/label_transfer.h): no deformation gives the input
// labels back wherever the mesh is and background elsewhere; a translation by whole voxels moves
// every label by exactly that many voxels; the output grid keeps the input's spacing and direction.
#include "workflows/label_transfer.h"

#include "support/model_fixture.h"

#include <gtest/gtest.h>

#include <cmath>

namespace tissuemesh {
namespace {

/// Voxel centres (x + 0.5, y + 0.5, z + 0.5) mm inside the block [0, 20] x [0, 10] x [0, 10] mm,
/// labelled 1, 2, 3 by x as the block's tissues, and 7 on the plane z < 2 (a label the mesh does
/// not know: labels are carried as they are).
LabelImage block_labels() {
  LabelImage img;
  img.dims = {20, 10, 10};
  img.origin = {0.5, 0.5, 0.5};
  img.labels.resize(img.voxel_count());
  for (int k = 0; k < 10; ++k)
    for (int j = 0; j < 10; ++j)
      for (int i = 0; i < 20; ++i) img.labels[img.index(i, j, k)] = k < 2 ? 7 : (i < 8 ? 1 : i < 14 ? 2 : 3);
  return img;
}

/// The label of `img` at physical point p when p is a voxel centre (else -1).
int label_at(const LabelImage& img, const Eigen::Vector3d& p) {
  const Eigen::Vector3d ijk = img.index_to_physical().inverse() * (p - img.origin);
  int idx[3];
  for (int a = 0; a < 3; ++a) {
    idx[a] = static_cast<int>(std::lround(ijk[a]));
    if (std::abs(ijk[a] - idx[a]) > 1e-9 || idx[a] < 0 || idx[a] >= img.dims[a]) return -1;
  }
  return img.at(idx[0], idx[1], idx[2]);
}

void expect_moved_by(const Eigen::Vector3d& t) {
  const Model model = test::block_model();
  const LabelImage in = block_labels();
  std::vector<Eigen::Vector3d> moved = model.nodes;
  for (Eigen::Vector3d& p : moved) p += t;
  const LabelImage out = transfer_labels(in, model, model.nodes, moved);
  EXPECT_EQ(out.spacing, in.spacing);
  EXPECT_EQ(out.direction, in.direction);
  int inside = 0;
  for (int k = 0; k < out.dims[2]; ++k)
    for (int j = 0; j < out.dims[1]; ++j)
      for (int i = 0; i < out.dims[0]; ++i) {
        const Eigen::Vector3d p = out.to_physical(Eigen::Vector3d(i, j, k));
        const int expected = label_at(in, p - t);
        const int got = out.at(i, j, k);
        if (expected < 0) {
          EXPECT_EQ(got, 0) << "outside the moved mesh at " << p.transpose();
        } else {
          EXPECT_EQ(got, expected) << "at " << p.transpose();
          ++inside;
        }
      }
  EXPECT_EQ(inside, static_cast<int>(in.voxel_count()));  // every input voxel landed once
}

TEST(LabelTransfer, NoDeformationGivesTheLabelsBack) { expect_moved_by(Eigen::Vector3d::Zero()); }

TEST(LabelTransfer, AWholeVoxelTranslationMovesEveryLabel) { expect_moved_by(Eigen::Vector3d(3.0, -2.0, 5.0)); }

}  // namespace
}  // namespace tissuemesh
