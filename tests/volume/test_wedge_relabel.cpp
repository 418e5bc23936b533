// The topology test of giving one tet to another tissue (volume/wedge_relabel.h), on a Kuhn-split
// box of one tissue with a tet of a second: a tet sharing a face with the second tissue may join
// it; one touching it only along an edge or at a node would pinch it and is refused. On a fan of
// three tets of one tissue, the middle one may not go (the tissue would split), an end may.
#include "volume/wedge_relabel.h"

#include "core/face_key.h"
#include "support/model_fixture.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <map>

namespace tissuemesh {
namespace {

// Face neighbours of a mesh whose tets do not change.
class Faces {
 public:
  explicit Faces(const TetMesh& m) : m_(m) {
    for (std::size_t t = 0; t < m.tets.size(); ++t)
      for (int f = 0; f < 4; ++f) {
        const auto& k = m.tets[t];
        faces_[face_key(k[(f + 1) % 4], k[(f + 2) % 4], k[(f + 3) % 4])].push_back(static_cast<int>(t));
      }
  }
  AcrossFace across() const {
    return [this](int a, int b, int c, int t) {
      const auto it = faces_.find(face_key(a, b, c));
      if (it == faces_.end()) return -1;
      for (int x : it->second)
        if (x != t) return x;
      return -1;
    };
  }
  // Shared nodes of tets a and b.
  int shared(int a, int b) const {
    int n = 0;
    for (int v : m_.tets[a]) n += std::count(m_.tets[b].begin(), m_.tets[b].end(), v);
    return n;
  }

 private:
  const TetMesh& m_;
  std::map<std::uint64_t, std::vector<int>> faces_;
};

// An interior tet of the box (none of its nodes on the box's faces), the first in mesh order.
int interior_tet(const TetMesh& m) {
  for (std::size_t t = 0; t < m.tets.size(); ++t) {
    bool inside = true;
    for (int v : m.tets[t]) inside = inside && m.points[v].minCoeff() > 0 && m.points[v].maxCoeff() < 8;
    if (inside) return static_cast<int>(t);
  }
  return -1;
}

// The first tet sharing exactly `nodes` nodes with tet x.
int sharing(const TetMesh& m, const Faces& faces, int x, int nodes) {
  for (std::size_t t = 0; t < m.tets.size(); ++t)
    if (static_cast<int>(t) != x && faces.shared(x, static_cast<int>(t)) == nodes) return static_cast<int>(t);
  return -1;
}

TEST(WedgeRelabel, JoinsThroughAFaceNeverPinches) {
  TetMesh m = test::box_mesh({0, 0, 0}, {8, 8, 8}, 4, 4, 4);
  std::fill(m.tissue_ids.begin(), m.tissue_ids.end(), 1);
  m.tissue_names = {"a", "b"};
  const int x = interior_tet(m);
  ASSERT_GE(x, 0);
  m.tissue_ids[x] = 2;
  const Faces faces(m);
  const int by_face = sharing(m, faces, x, 3), by_edge = sharing(m, faces, x, 2), by_node = sharing(m, faces, x, 1);
  ASSERT_GE(by_face, 0);
  ASSERT_GE(by_edge, 0);
  ASSERT_GE(by_node, 0);
  EXPECT_TRUE(relabel_keeps_topology(m, by_face, 2, faces.across()));
  EXPECT_FALSE(relabel_keeps_topology(m, by_edge, 2, faces.across()));  // b pinched along an edge
  EXPECT_FALSE(relabel_keeps_topology(m, by_node, 2, faces.across()));  // b pinched at a node
  EXPECT_TRUE(relabel_keeps_topology(m, by_face, 1, faces.across()));   // no change at all
}

TEST(WedgeRelabel, NeverSplitsTheTissueItLeaves) {
  // Three tets of tissue a in an open fan around the edge (0, 1) on the boundary.
  TetMesh m;
  m.points = {{0, 0, 0}, {0, 0, 1}, {1, 0, 0}, {0.5, 0.866, 0}, {-0.5, 0.866, 0}, {-1, 0, 0}};
  m.tets = {{0, 2, 3, 1}, {0, 3, 4, 1}, {0, 4, 5, 1}};
  m.tissue_ids = {1, 1, 1};
  m.tissue_names = {"a", "b"};
  const Faces faces(m);
  EXPECT_FALSE(relabel_keeps_topology(m, 1, 2, faces.across()));  // a would be two pieces meeting at an edge
  EXPECT_TRUE(relabel_keeps_topology(m, 0, 2, faces.across()));   // an end of the fan may go
  EXPECT_TRUE(relabel_keeps_topology(m, 2, 2, faces.across()));
}

TEST(WedgeRelabel, FlatMeansVolumeBelowAFifthOfTheRegularTet) {
  TetMesh m;
  m.points = {{0, 0, 0}, {2, 0, 0}, {1, 1.7320508, 0}, {1, 0.57735, 1.6329932}};
  m.tets = {{0, 1, 2, 3}};
  m.tissue_ids = {1};
  m.tissue_names = {"a"};
  EXPECT_FALSE(is_flat_wedge(m, 0));  // regular
  m.points[3].z() = 0.15 * 1.6329932;
  EXPECT_TRUE(is_flat_wedge(m, 0));   // 0.15 of its height: 0.15 of the regular volume
  m.points[3].z() = 0.25 * 1.6329932;
  EXPECT_FALSE(is_flat_wedge(m, 0));
}

}  // namespace
}  // namespace tissuemesh
