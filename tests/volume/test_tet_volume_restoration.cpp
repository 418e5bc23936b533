// Volume restoration of a tet mesh (volume/tet_volume_restoration.h): CGAL Mesh_3 resampling a
// remeshed surface coarsely cuts its curved sheets, so every tissue's tets fill less than the
// surface encloses. Moving the mesh's boundary and interface nodes gives the volumes back to the
// tolerance with every tet still positive and no tet's smallest dihedral lowered under 10 degrees;
// interior nodes and the connectivity do not change, and the mesh stays conforming. Asked for far
// more than a tight spot allows, nodes are held and no tet flattens.
#include "core/errors.h"
#include "quality/conformity.h"
#include "quality/mesh_interfaces.h"
#include "quality/mesh_quality.h"
#include "support/complex_meshes.h"
#include "volume/complex_mesher.h"
#include "volume/tet_volume_restoration.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <iostream>

using namespace tissuemesh;
using namespace tissuemesh::test;

namespace {

// The nested spheres' remeshed surface and a CGAL mesh of it at facets `factor` times its edge.
struct CoarseMesh {
  RemeshResult surface;
  TetMesh mesh;
};

CoarseMesh coarse_mesh(double factor) {
  CoarseMesh c{remeshed(nested_spheres(), 2, 300), {}};
  VolumeMeshParams params;
  params.surface_edge_factor = factor;
  params.cell_edge_factor = 1.5 * factor;
  params.facet_distance_mm = 0.3 * factor;
  Progress progress;
  const double h = c.surface.edge_length_mm;
  c.mesh = mesh_complex(c.surface.surface, [h](const Eigen::Vector3d&) { return h; }, params, progress).mesh;
  return c;
}

double min_dihedral(const TetMesh& m) { return compute_quality(m).total.min_dihedral_deg; }

// Conforming, nothing inverted, no tet under `floor_deg`.
void expect_valid_above(const TetMesh& m, double floor_deg) {
  const ConformityReport conformity = check_conformity(m);
  EXPECT_TRUE(conformity.conforming());
  EXPECT_EQ(conformity.inverted_tets, 0u);
  EXPECT_GE(min_dihedral(m), floor_deg);
}

// Every node on a boundary or interface.
std::vector<char> surface_nodes(const TetMesh& m) {
  std::vector<int> node_of_point;
  interface_surface(m, &node_of_point);
  std::vector<char> on(m.points.size(), 0);
  for (int n : node_of_point) on[n] = 1;
  return on;
}

}  // namespace

TEST(TetVolumeRestoration, ACoarseResamplingGetsTheSurfaceVolumesBack) {
  CoarseMesh c = coarse_mesh(2.5);
  const std::map<int, double> reference = enclosed_volumes(c.surface.surface);
  const std::vector<double> before = tissue_volumes(c.mesh);
  double worst_before = 0.0;
  for (const auto& [id, v] : reference) worst_before = std::max(worst_before, std::abs(before[id] / v - 1.0));
  ASSERT_GT(worst_before, 5e-3) << "the coarse tets must lose volume for the test to mean something";
  const TetMesh original = c.mesh;
  const double floor_deg = std::min(min_dihedral(original), 10.0);

  const TetVolumeRestoration r = restore_tet_volumes(c.mesh, reference);
  const std::vector<double> after = tissue_volumes(c.mesh);
  std::cout << "[ volume   ] worst tissue " << worst_before << " -> ";
  for (const auto& [id, v] : reference) {
    EXPECT_NEAR(after[id] / v, 1.0, 1e-3) << "tissue " << id;
    std::cout << after[id] / v - 1.0 << " ";
  }
  std::cout << "in " << r.offsets.rounds << " rounds, " << r.nodes_moved << " nodes, largest move " << r.max_offset_mm
            << " mm\n";
  EXPECT_GE(r.offsets.rounds, 1);
  EXPECT_GT(r.nodes_moved, 0u);
  EXPECT_LT(r.max_offset_mm, c.surface.edge_length_mm);  // a correction, not a new boundary
  EXPECT_EQ(c.mesh.tets, original.tets);
  EXPECT_EQ(c.mesh.tissue_ids, original.tissue_ids);
  const std::vector<char> on_surface = surface_nodes(original);
  std::size_t moved = 0;
  for (std::size_t n = 0; n < original.points.size(); ++n) {
    if (c.mesh.points[n] == original.points[n]) continue;
    ++moved;
    EXPECT_TRUE(on_surface[n]) << "interior node " << n << " moved";
  }
  EXPECT_EQ(moved, r.nodes_moved);
  expect_valid_above(c.mesh, floor_deg);
}

namespace {

// The coarse mesh's inner ball asked for `factor` times its volume (the outer tissue giving it up):
// the volumes before and after and the restoration, every tet checked to keep its dihedral floor.
struct InnerBallAsk {
  std::vector<double> before, after;
  std::map<int, double> reference;
  TetVolumeRestoration r;
};
InnerBallAsk ask_inner_ball(double factor) {
  CoarseMesh c = coarse_mesh(2.5);
  InnerBallAsk a;
  a.before = tissue_volumes(c.mesh);
  a.reference = {{1, a.before[1] - (factor - 1.0) * a.before[2]}, {2, factor * a.before[2]}};
  const double floor_deg = std::min(min_dihedral(c.mesh), 10.0);
  a.r = restore_tet_volumes(c.mesh, a.reference);
  a.after = tissue_volumes(c.mesh);
  std::cout << "[ volume   ] inner ball " << a.after[2] / a.before[2] << " of " << factor << " asked, "
            << a.r.offsets.frozen_vertices << " nodes held, " << a.r.offsets.rounds << " rounds\n";
  expect_valid_above(c.mesh, floor_deg);
  return a;
}

}  // namespace

// Asked for 3 times the inner ball (a radius of 7.2 mm inside the outer 9 mm), the tets between
// the interface and the outer boundary would flatten at some nodes: the rounds hold those nodes,
// and every tet keeps its dihedral floor whatever the volumes reach.
TEST(TetVolumeRestoration, NodesAreHeldRatherThanFlattenATet) {
  const InnerBallAsk a = ask_inner_ball(3.0);
  EXPECT_GT(a.r.offsets.frozen_vertices, 0u);
  EXPECT_LT(a.after[2], a.reference.at(2));  // the held nodes keep it from the volume asked
  EXPECT_GT(a.after[2], a.before[2]);        // it grew as far as it could
}

// Asked for 2.3 times the inner ball (a radius of 6.6 mm), more than many interface nodes may
// move in one round: the moves are clipped at each node's shortest edge, the rounds go on, and
// the volume asked is reached with every tet at its dihedral floor.
TEST(TetVolumeRestoration, ALargeAskIsReachedOverRoundsOfClippedMoves) {
  const InnerBallAsk a = ask_inner_ball(2.3);
  EXPECT_NEAR(a.after[2] / a.reference.at(2), 1.0, 1e-3);
  EXPECT_NEAR(a.after[1] / a.reference.at(1), 1.0, 1e-3);
  EXPECT_GT(a.r.offsets.rounds, 1);
}

// The same 2.3 times, with no node allowed to move more than 0.2 mm in all: every node stays
// within it, and the ball grows as far as that lets it.
TEST(TetVolumeRestoration, NoNodeMovesFurtherThanTheBound) {
  CoarseMesh c = coarse_mesh(2.5);
  const TetMesh original = c.mesh;
  const std::vector<double> before = tissue_volumes(c.mesh);
  const std::map<int, double> reference = {{1, before[1] - 1.3 * before[2]}, {2, 2.3 * before[2]}};
  const double floor_deg = std::min(min_dihedral(c.mesh), 10.0);
  const TetVolumeRestoration r = restore_tet_volumes(c.mesh, reference, 0.2);
  double largest = 0.0;
  for (std::size_t n = 0; n < original.points.size(); ++n)
    largest = std::max(largest, (c.mesh.points[n] - original.points[n]).norm());
  EXPECT_LE(largest, 0.2 + 1e-12);
  EXPECT_GT(largest, 0.15);  // the bound, not the ask, stopped it
  const std::vector<double> after = tissue_volumes(c.mesh);
  EXPECT_GT(after[2], before[2]);
  EXPECT_LT(after[2], 0.9 * reference.at(2));
  expect_valid_above(c.mesh, floor_deg);
}

TEST(TetVolumeRestoration, BadReferenceIsAnInputError) {
  CoarseMesh c = coarse_mesh(2.5);
  EXPECT_THROW(restore_tet_volumes(c.mesh, {{3, 100.0}}), InputError);
  EXPECT_THROW(restore_tet_volumes(c.mesh, {{1, -1.0}}), InputError);
  EXPECT_THROW(restore_tet_volumes(c.mesh, {{1, 100.0}}, 0.0), InputError);
}
