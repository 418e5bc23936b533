// Opening of boundary pinches on manufactured meshes: boxes (6 tets each) that touch along an
// edge. The repair must make the mesh conform, remove only tets of the smaller side around the
// edge, report their count and volume by tissue, and leave a mesh without pinches untouched.
#include "volume/boundary_pinches.h"

#include "quality/conformity.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>

using namespace tissuemesh;

namespace {

struct PointLess {
  bool operator()(const Eigen::Vector3d& a, const Eigen::Vector3d& b) const {
    return std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3);
  }
};

// Adds the axis-aligned box [lo, lo + size] as the 6 tets around its main diagonal (every box
// edge is a tet edge), positively oriented, sharing nodes with what is there at the same place.
void add_box(TetMesh& m, std::map<Eigen::Vector3d, int, PointLess>& nodes, const Eigen::Vector3d& lo,
             const Eigen::Vector3d& size, int tissue) {
  auto node = [&](const Eigen::Vector3d& p) {
    auto [it, fresh] = nodes.emplace(p, static_cast<int>(m.points.size()));
    if (fresh) m.points.push_back(p);
    return it->second;
  };
  const int perms[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  for (const auto& p : perms) {
    Eigen::Vector3d v = lo;
    std::array<int, 4> t{};
    t[0] = node(v);
    for (int k = 0; k < 3; ++k) {
      v[p[k]] += size[p[k]];
      t[k + 1] = node(v);
    }
    if (signed_tet_volume(m.points[t[0]], m.points[t[1]], m.points[t[2]], m.points[t[3]]) < 0) std::swap(t[2], t[3]);
    m.tets.push_back(t);
    m.tissue_ids.push_back(tissue);
  }
}

double total_volume(const TetMesh& m) {
  double v = 0;
  for (const auto& t : m.tets) v += signed_tet_volume(m.points[t[0]], m.points[t[1]], m.points[t[2]], m.points[t[3]]);
  return v;
}

std::size_t tets_on_edge(const TetMesh& m, const Eigen::Vector3d& a, const Eigen::Vector3d& b, int tissue) {
  std::size_t n = 0;
  for (std::size_t t = 0; t < m.tets.size(); ++t) {
    if (m.tissue_ids[t] != tissue) continue;
    int hits = 0;
    for (int v : m.tets[t]) hits += (m.points[v] - a).norm() < 1e-12 || (m.points[v] - b).norm() < 1e-12;
    n += hits == 2;
  }
  return n;
}

}  // namespace

TEST(BoundaryPinches, BoxesTouchingAlongAnEdgeAreSeparatedOnTheSmallerSide) {
  // Tissue 2 (a box of a quarter the volume) comes first in tet order, so the choice must go by volume.
  TetMesh m;
  m.tissue_names = {"big", "small"};
  std::map<Eigen::Vector3d, int, PointLess> nodes;
  add_box(m, nodes, {1, 1, 0}, {0.5, 0.5, 1}, 2);
  add_box(m, nodes, {0, 0, 0}, {1, 1, 1}, 1);
  ASSERT_EQ(check_conformity(m).nonmanifold_boundary_edges, 1u);
  const std::size_t small_on_edge = tets_on_edge(m, {1, 1, 0}, {1, 1, 1}, 2);
  ASSERT_GT(small_on_edge, 0u);
  const std::size_t tets_before = m.tets.size();
  const std::size_t big_on_edge = tets_on_edge(m, {1, 1, 0}, {1, 1, 1}, 1);

  const BoundaryPinchRepair r = open_boundary_pinches(m);
  EXPECT_EQ(r.edges_found, 1u);
  EXPECT_EQ(r.edges_left, 0u);
  EXPECT_EQ(r.tets_removed, small_on_edge);
  EXPECT_EQ(r.removed_per_tissue, (std::vector<std::size_t>{0, small_on_edge}));
  EXPECT_EQ(r.volume_per_tissue_mm3[0], 0.0);
  EXPECT_NEAR(r.volume_removed_mm3, r.volume_per_tissue_mm3[1], 1e-15);
  EXPECT_NEAR(total_volume(m), 1.0 + 0.25 - r.volume_removed_mm3, 1e-12);
  EXPECT_EQ(m.tets.size(), tets_before - small_on_edge);
  EXPECT_EQ(tets_on_edge(m, {1, 1, 0}, {1, 1, 1}, 1), big_on_edge);  // the big side is untouched

  const ConformityReport c = check_conformity(m);
  EXPECT_TRUE(c.conforming()) << format_conformity_table(c, m.tissue_names);
  EXPECT_EQ(c.orphan_nodes, 0u);
}

TEST(BoundaryPinches, EqualSidesKeepTheFirstAndTheResultConforms) {
  TetMesh m;
  m.tissue_names = {"a"};
  std::map<Eigen::Vector3d, int, PointLess> nodes;
  add_box(m, nodes, {0, 0, 0}, {1, 1, 1}, 1);
  add_box(m, nodes, {1, 1, 0}, {1, 1, 1}, 1);
  add_box(m, nodes, {2, 2, 0}, {1, 1, 1}, 1);  // a second pinch, at the next edge of the chain
  ASSERT_EQ(check_conformity(m).nonmanifold_boundary_edges, 2u);
  const BoundaryPinchRepair r = open_boundary_pinches(m);
  EXPECT_EQ(r.edges_found, 2u);
  EXPECT_EQ(r.edges_left, 0u);
  EXPECT_GE(r.passes, 1);
  EXPECT_TRUE(check_conformity(m).conforming());
  EXPECT_NEAR(total_volume(m), 3.0 - r.volume_removed_mm3, 1e-12);
  EXPECT_GT(r.volume_removed_mm3, 0.0);
  EXPECT_LT(r.volume_removed_mm3, 1.0);
}

TEST(BoundaryPinches, AMeshWithoutPinchesIsLeftAsItIs) {
  TetMesh m;
  m.tissue_names = {"a", "b"};
  std::map<Eigen::Vector3d, int, PointLess> nodes;
  add_box(m, nodes, {0, 0, 0}, {1, 1, 1}, 1);
  add_box(m, nodes, {1, 0, 0}, {1, 1, 1}, 2);  // face to face: an interface, no pinch
  const TetMesh before = m;
  const BoundaryPinchRepair r = open_boundary_pinches(m);
  EXPECT_EQ(r.edges_found, 0u);
  EXPECT_EQ(r.tets_removed, 0u);
  EXPECT_EQ(r.passes, 0);
  EXPECT_EQ(m.tets, before.tets);
  EXPECT_EQ(m.points, before.points);
  EXPECT_EQ(m.tissue_ids, before.tissue_ids);
}
