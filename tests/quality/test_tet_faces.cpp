// number_tet_faces (quality/tet_faces.h): one id per distinct face, shared by the two tets on it.
#include "quality/tet_faces.h"

#include <gtest/gtest.h>

#include <set>

using namespace tissuemesh;

TEST(TetFaces, TwoTetsOnOneFaceShareItsIdAndNoOther) {
  // Tets 0 and 1 share the face {1, 2, 3}: face 0 of tet 0 (opposite node 0) and face 3 of tet 1
  // (opposite node 4), given in another node order.
  const std::vector<std::array<int, 4>> tets{{0, 1, 2, 3}, {3, 2, 1, 4}};
  const TetFaces f = number_tet_faces(tets);
  ASSERT_EQ(f.id.size(), 8u);
  EXPECT_EQ(f.count, 7u);
  EXPECT_EQ(f.of(0, 0), f.of(1, 3));
  std::set<int> ids(f.id.begin(), f.id.end());
  EXPECT_EQ(ids.size(), 7u);
  EXPECT_EQ(*ids.begin(), 0);
  EXPECT_EQ(*ids.rbegin(), 6);
  EXPECT_EQ(number_tet_faces({}).count, 0u);
}
