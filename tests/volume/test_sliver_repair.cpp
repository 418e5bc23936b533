// Sliver repair passes on a real CGAL mesh: flips must keep tissue volumes, interfaces and
// conformity exactly and only raise quality; boundary peeling only removes flat outer caps;
// smoothing moves only nodes whose moves leave every tissue's boundary where it was.
#include "volume/boundary_slivers.h"
#include "quality/conformity.h"
#include "volume/direct_mesher.h"
#include "quality/mesh_quality.h"
#include "volume/mesh3_optimisation.h"
#include "volume/sliver_flips.h"
#include "volume/sliver_smoothing.h"
#include "support/model_fixture.h"
#include "support/test_helpers.h"
#include "support/tolerances.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <iostream>
#include <array>
#include <map>
#include <set>

using namespace tissuemesh;

namespace {

// Nested spheres meshed without any repair, so that slivers remain for the passes to work on.
TetMesh unrepaired_mesh() {
  const LabelImage img = test::nested_spheres();
  DirectMeshParams p;
  p.facet_size_mm = 2.0;
  p.facet_distance_mm = 0.3;
  p.cell_size_mm = 3.0;
  p.refine_tissue = "";
  p.optimise.exude = false;
  p.optimise.remove_boundary_slivers_deg = 0;
  p.optimise.flip_slivers_below_deg = 0;
  p.optimise.smooth_slivers_below_deg = 0;
  Progress progress;
  return mesh_labels_direct(img, {"outer", "inner"}, p, progress).mesh;
}

// Faces between different tissues or on the boundary, as (sorted nodes) -> tissue pair.
std::map<std::array<int, 3>, std::pair<int, int>> interface_faces(const TetMesh& m) {
  std::map<std::array<int, 3>, std::vector<int>> faces;
  for (std::size_t t = 0; t < m.tets.size(); ++t)
    for (int f = 0; f < 4; ++f) {
      std::array<int, 3> k{m.tets[t][(f + 1) % 4], m.tets[t][(f + 2) % 4], m.tets[t][(f + 3) % 4]};
      std::sort(k.begin(), k.end());
      faces[k].push_back(m.tissue_ids[t]);
    }
  std::map<std::array<int, 3>, std::pair<int, int>> out;
  for (const auto& [k, ids] : faces) {
    const int a = ids[0], b = ids.size() > 1 ? ids[1] : 0;
    if (a != b) out[k] = {std::min(a, b), std::max(a, b)};
  }
  return out;
}

// Number of face-connected pieces of each tissue (tissue id -> count).
std::map<int, int> tissue_pieces(const TetMesh& m) {
  std::vector<int> parent(m.tets.size());
  for (std::size_t t = 0; t < parent.size(); ++t) parent[t] = static_cast<int>(t);
  std::function<int(int)> find = [&](int x) { return parent[x] == x ? x : parent[x] = find(parent[x]); };
  std::map<std::array<int, 3>, int> first;
  for (std::size_t t = 0; t < m.tets.size(); ++t)
    for (int f = 0; f < 4; ++f) {
      std::array<int, 3> k{m.tets[t][(f + 1) % 4], m.tets[t][(f + 2) % 4], m.tets[t][(f + 3) % 4]};
      std::sort(k.begin(), k.end());
      auto [it, fresh] = first.emplace(k, static_cast<int>(t));
      if (!fresh && m.tissue_ids[it->second] == m.tissue_ids[t]) parent[find(it->second)] = find(static_cast<int>(t));
    }
  std::map<int, int> pieces;
  for (std::size_t t = 0; t < m.tets.size(); ++t)
    if (find(static_cast<int>(t)) == static_cast<int>(t)) ++pieces[m.tissue_ids[t]];
  return pieces;
}

}  // namespace

TEST(SliverFlips, KeepInterfacesVolumesAndConformityAndRaiseQuality) {
  TetMesh mesh = unrepaired_mesh();
  const auto faces_before = interface_faces(mesh);
  const QualityReport before = compute_quality(mesh);
  const SliverFlipResult r = flip_slivers(mesh, 15.0, /*allow_interface_flips=*/false);
  EXPECT_GT(r.edge_removals + r.flips_23, 0u);
  EXPECT_TRUE(check_conformity(mesh).conforming());
  EXPECT_EQ(interface_faces(mesh), faces_before);  // no interface or boundary face changed
  const QualityReport after = compute_quality(mesh);
  for (std::size_t t = 0; t < before.tissues.size(); ++t)
    EXPECT_NEAR(after.tissues[t].volume_mm3, before.tissues[t].volume_mm3,
                test::kRelativeRoundoff * before.tissues[t].volume_mm3);
  EXPECT_EQ(after.total.vertices, before.total.vertices);  // nodes neither added nor lost
  EXPECT_GE(after.total.min_dihedral_deg, before.total.min_dihedral_deg);
  EXPECT_LT(after.total.tets_below_10deg, before.total.tets_below_10deg);
}

TEST(SliverFlips, AreDeterministic) {
  TetMesh a = unrepaired_mesh(), b = unrepaired_mesh();
  flip_slivers(a, 15.0, true);
  flip_slivers(b, 15.0, true);
  EXPECT_EQ(a.tets, b.tets);
  EXPECT_EQ(a.tissue_ids, b.tissue_ids);
}

TEST(SliverFlips, InterfaceFlipsMoveOnlyTheReportedWedgeVolume) {
  TetMesh inside_only = unrepaired_mesh(), across = unrepaired_mesh();
  const QualityReport before = compute_quality(across);
  const auto pieces_before = tissue_pieces(across);
  flip_slivers(inside_only, 15.0, false);
  const SliverFlipResult r = flip_slivers(across, 15.0, true);
  EXPECT_GT(r.interface_flips, 0u);
  EXPECT_TRUE(check_conformity(across).conforming());
  EXPECT_EQ(tissue_pieces(across), pieces_before);  // no tissue split (e.g. pinched at an edge)
  const QualityReport after = compute_quality(across);
  // The total is unchanged; each tissue changes by at most the wedge volume moved.
  EXPECT_NEAR(after.total.volume_mm3, before.total.volume_mm3, test::kRelativeRoundoff * before.total.volume_mm3);
  for (std::size_t t = 0; t < before.tissues.size(); ++t)
    EXPECT_LE(std::abs(after.tissues[t].volume_mm3 - before.tissues[t].volume_mm3),
              r.volume_relabelled_mm3 + test::kRelativeRoundoff * before.total.volume_mm3);
  EXPECT_LE(after.total.tets_below_10deg, compute_quality(inside_only).total.tets_below_10deg);
}

TEST(BoundarySlivers, KeepAnEdgeThatIsAlreadyOnTheBoundary) {
  // An open fan of three tets around edge cd (on the boundary). The middle tet is a 5-degree
  // sliver whose two outer faces meet at a1-a2; removing it would give cd four boundary faces.
  TetMesh m;
  auto at = [](double deg) { return Eigen::Vector3d(std::cos(deg * M_PI / 180), std::sin(deg * M_PI / 180), 0.5); };
  m.points = {{0, 0, 0}, {0, 0, 1}, at(0), at(80), at(85), at(180)};
  m.tets = {{0, 1, 2, 3}, {0, 1, 3, 4}, {0, 1, 4, 5}};
  for (auto& t : m.tets)
    if (signed_tet_volume(m.points[t[0]], m.points[t[1]], m.points[t[2]], m.points[t[3]]) < 0) std::swap(t[2], t[3]);
  m.tissue_ids = {1, 1, 1};
  m.tissue_names = {"a"};
  ASSERT_LT(compute_quality(m).total.min_dihedral_deg, 10.0);
  const BoundarySliverRemoval r = remove_boundary_slivers(m, 10.0);
  EXPECT_EQ(check_conformity(m).nonmanifold_boundary_edges, 0u);
  EXPECT_EQ(r.tets_removed, 0u);
}

TEST(BoundarySlivers, RemoveOnlyFlatOuterCaps) {
  TetMesh mesh = unrepaired_mesh();
  const std::size_t tets_before = mesh.tets.size();
  const QualityReport before = compute_quality(mesh);
  const BoundarySliverRemoval r = remove_boundary_slivers(mesh, 10.0);
  EXPECT_EQ(mesh.tets.size(), tets_before - r.tets_removed);
  const ConformityReport c = check_conformity(mesh);
  EXPECT_TRUE(c.conforming());  // no orphan node, boundary still closed and manifold
  const QualityReport after = compute_quality(mesh);
  EXPECT_NEAR(after.total.volume_mm3, before.total.volume_mm3 - r.volume_removed_mm3,
              test::kRelativeRoundoff * before.total.volume_mm3);
  // The inner sphere never touches the outside, so none of its tets can be a boundary cap.
  EXPECT_EQ(r.removed_per_tissue[1], 0u);
  EXPECT_EQ(after.tissues[1].tets, before.tissues[1].tets);
}

namespace {

// A 8 x 8 x 4 mm box on a 2 mm grid whose node at `at` (mm) is pushed by `by`: its tets turn
// into slivers. Returns the node's index.
int push_node(TetMesh& mesh, const Eigen::Vector3d& at, const Eigen::Vector3d& by) {
  for (std::size_t i = 0; i < mesh.points.size(); ++i)
    if ((mesh.points[i] - at).norm() < 1e-12) {
      mesh.points[i] += by;
      return static_cast<int>(i);
    }
  ADD_FAILURE() << "no node at " << at.transpose();
  return 0;
}

}  // namespace

// A free node (inside the box) and a node of the flat bottom face are pushed along grid diagonals
// until their tets are slivers. Smoothing moves them back to good positions: the free node
// anywhere, the bottom node only within its plane (z stays exactly 0, so the box keeps its
// shape), nothing else of the topology or any volume changes.
TEST(SliverSmoothing, MovesFreeAndFlatBoundaryNodesWithoutChangingTheBox) {
  TetMesh mesh = test::box_mesh({0, 0, 0}, {8, 8, 4}, 4, 4, 2);
  const int inner = push_node(mesh, {4, 4, 2}, {1.7, 1.7, 1.7});
  const int bottom = push_node(mesh, {4, 4, 0}, {1.8, 1.8, 0});
  const QualityReport before = compute_quality(mesh);
  ASSERT_EQ(check_conformity(mesh).inverted_tets, 0u);
  ASSERT_LT(before.total.min_dihedral_deg, 10.0);
  const auto tets = mesh.tets;
  const auto faces = interface_faces(mesh);

  const SliverSmoothingResult r = smooth_slivers(mesh, 15.0);
  EXPECT_GE(r.moved_vertices, 2u);
  EXPECT_EQ(mesh.tets, tets);  // positions only
  EXPECT_EQ(interface_faces(mesh), faces);
  EXPECT_EQ(mesh.points[static_cast<std::size_t>(bottom)].z(), 0.0);  // still on the bottom face
  EXPECT_GT((mesh.points[static_cast<std::size_t>(inner)] - Eigen::Vector3d(5.7, 5.7, 3.7)).norm(), 0.1);
  const QualityReport after = compute_quality(mesh);
  EXPECT_NEAR(after.total.volume_mm3, 256.0, test::kRelativeRoundoff * 256.0);
  EXPECT_EQ(check_conformity(mesh).inverted_tets, 0u);
  std::cout << "[ smooth   ] box: min dihedral " << before.total.min_dihedral_deg << " -> "
            << after.total.min_dihedral_deg << " deg\n";
  EXPECT_GE(after.total.min_dihedral_deg, 15.0);  // the unpushed grid's tets are 35.3-90 degrees
}

// On a CGAL mesh of curved tissues only free nodes may move: every node on the boundary or an
// interface keeps its position, so interfaces, boundary and each tissue's volume are unchanged.
TEST(SliverSmoothing, KeepsCurvedInterfacesAndVolumesOfACgalMeshAndRaisesQuality) {
  TetMesh mesh = unrepaired_mesh();
  const TetMesh original = mesh;
  const QualityReport before = compute_quality(mesh);
  const SliverSmoothingResult r = smooth_slivers(mesh, 15.0);
  EXPECT_GT(r.moved_vertices, 0u);
  EXPECT_EQ(mesh.tets, original.tets);
  std::set<int> on_surface;
  for (const auto& [face, pair] : interface_faces(mesh)) on_surface.insert(face.begin(), face.end());
  std::size_t moved = 0;
  for (std::size_t i = 0; i < mesh.points.size(); ++i) {
    if (mesh.points[i] == original.points[i]) continue;
    ++moved;
    EXPECT_EQ(on_surface.count(static_cast<int>(i)), 0u) << "surface node " << i << " moved";
  }
  EXPECT_GT(moved, 0u);
  const QualityReport after = compute_quality(mesh);
  for (std::size_t t = 0; t < before.tissues.size(); ++t)
    EXPECT_NEAR(after.tissues[t].volume_mm3, before.tissues[t].volume_mm3,
                test::kRelativeRoundoff * before.tissues[t].volume_mm3);
  EXPECT_GE(after.total.min_dihedral_deg, before.total.min_dihedral_deg);
  EXPECT_LT(after.total.tets_below_10deg, before.total.tets_below_10deg);
  EXPECT_EQ(check_conformity(mesh).inverted_tets, 0u);
  TetMesh again = original;
  smooth_slivers(again, 15.0);
  EXPECT_EQ(again.points, mesh.points);  // deterministic
}

// A node whose star already holds an inverted tet is not a smoothing case (the mesher never
// hands one over): it is left where it is, and nothing else breaks.
TEST(SliverSmoothing, LeavesANodeWithAnInvertedTetAlone) {
  TetMesh mesh = test::box_mesh({0, 0, 0}, {8, 8, 4}, 4, 4, 2);
  const int inner = push_node(mesh, {4, 4, 2}, {0, 0, 2.2});
  ASSERT_GT(check_conformity(mesh).inverted_tets, 0u);
  const Eigen::Vector3d pushed = mesh.points[static_cast<std::size_t>(inner)];
  smooth_slivers(mesh, 15.0);
  EXPECT_EQ(mesh.points[static_cast<std::size_t>(inner)], pushed);
}

namespace {

TetMesh oriented_mesh(std::vector<Eigen::Vector3d> points, std::vector<std::array<int, 4>> tets, std::vector<int> ids,
                      std::vector<std::string> names) {
  TetMesh m;
  m.points = std::move(points);
  m.tets = std::move(tets);
  for (auto& t : m.tets)
    if (signed_tet_volume(m.points[t[0]], m.points[t[1]], m.points[t[2]], m.points[t[3]]) < 0) std::swap(t[2], t[3]);
  m.tissue_ids = std::move(ids);
  m.tissue_names = std::move(names);
  return m;
}

}  // namespace

// The 2.1K phantom's flattest tet (9.04 degrees; nodes rounded to 0.1 um, shifted to the origin):
// a fat sliver pqrs on a fat|fgt interface whose bad angles sit at edges of the interface, next to
// a flat fgt wedge pqse whose two faces on edge pq both border fat (the sliver and tet pqre). The
// wedge is not the sliver itself, so only giving the *neighbour* wedge to fat frees edge pq: its
// ring is then all fat and the 3-2 flip replaces the three tets by two of 32-34 degrees.
TEST(SliverFlips, InterfaceFlipGivesANeighbouringFlatWedgeToTheSliversTissue) {
  const Eigen::Vector3d p(0, 0, 0), q(-0.1304, 1.6121, -0.0062), r(-0.7640, 0.7513, -0.1202),
      s(0.7364, 0.8938, -0.0629), e(-1.0202, 0.8328, 0.6365);
  const Eigen::Vector3d f = (s + e) - (p + q) / 2;  // fgt beyond the wedge's edge se
  // 0 p, 1 q, 2 r, 3 s, 4 e, 5 f; fat = 1, fgt = 2.
  TetMesh m = oriented_mesh({p, q, r, s, e, f}, {{0, 1, 2, 3}, {0, 1, 3, 4}, {0, 1, 2, 4}, {0, 3, 4, 5}, {1, 3, 4, 5}},
                            {1, 2, 1, 2, 2}, {"fat", "fgt"});
  const auto& w = m.tets[1];
  const double wedge_volume = signed_tet_volume(m.points[w[0]], m.points[w[1]], m.points[w[2]], m.points[w[3]]);
  const QualityReport before = compute_quality(m);
  ASSERT_LT(before.total.min_dihedral_deg, 10.0);
  ASSERT_TRUE(check_conformity(m).conforming());

  TetMesh inside_only = m;
  flip_slivers(inside_only, 15.0, /*allow_interface_flips=*/false);
  EXPECT_LT(compute_quality(inside_only).total.min_dihedral_deg, 10.0);  // no flip inside fat helps

  const SliverFlipResult res = flip_slivers(m, 15.0, true);
  EXPECT_EQ(res.interface_flips, 1u);
  EXPECT_NEAR(res.volume_relabelled_mm3, wedge_volume, test::kRelativeRoundoff * wedge_volume);
  EXPECT_TRUE(check_conformity(m).conforming());
  for (const auto& t : m.tets)  // edge pq is gone
    EXPECT_FALSE(std::count(t.begin(), t.end(), 0) && std::count(t.begin(), t.end(), 1));
  const QualityReport after = compute_quality(m);
  EXPECT_GE(after.total.min_dihedral_deg, 10.0);
  EXPECT_NEAR(after.total.volume_mm3, before.total.volume_mm3, test::kRelativeRoundoff * before.total.volume_mm3);
  EXPECT_NEAR(after.tissues[0].volume_mm3, before.tissues[0].volume_mm3 + wedge_volume,
              test::kRelativeRoundoff * before.total.volume_mm3);  // fat gains exactly the wedge
  EXPECT_NEAR(after.tissues[1].volume_mm3, before.tissues[1].volume_mm3 - wedge_volume,
              test::kRelativeRoundoff * before.total.volume_mm3);
  EXPECT_EQ(tissue_pieces(m), (std::map<int, int>{{1, 1}, {2, 1}}));
}

// The box's bottom is bent into a shallow bowl (z = 0.01 (x-4)^2 + 0.01 (y-4)^2: face normals
// within about 3 degrees of vertical) and its middle bottom node pushed along it until its tets
// are slivers. Exactly-planar smoothing cannot move it; near-planar smoothing slides it in the
// plane that keeps the volume, so the box's volume is unchanged while its worst angle recovers.
TEST(SliverSmoothing, SlidesANearlyFlatBoundaryNodeKeepingTheVolume) {
  TetMesh mesh = test::box_mesh({0, 0, 0}, {8, 8, 4}, 4, 4, 2);
  for (auto& x : mesh.points)
    if (x.z() == 0.0) x.z() = 0.01 * ((x.x() - 4) * (x.x() - 4) + (x.y() - 4) * (x.y() - 4));
  const int bottom = push_node(mesh, {4, 4, 0}, {1.8, 1.8, 0.01 * 2 * 1.8 * 1.8});  // along the bowl
  ASSERT_EQ(check_conformity(mesh).inverted_tets, 0u);
  const QualityReport before = compute_quality(mesh);
  ASSERT_LT(before.total.min_dihedral_deg, 10.0);
  const TetMesh original = mesh;
  const auto faces = interface_faces(mesh);

  TetMesh flat_only = mesh;
  smooth_slivers(flat_only, 15.0, /*near_planar_deg=*/0.0);
  EXPECT_EQ(flat_only.points[static_cast<std::size_t>(bottom)], mesh.points[static_cast<std::size_t>(bottom)]);

  smooth_slivers(mesh, 15.0, /*near_planar_deg=*/5.0);
  const Eigen::Vector3d moved = mesh.points[static_cast<std::size_t>(bottom)] - original.points[static_cast<std::size_t>(bottom)];
  EXPECT_GT(moved.norm(), 0.1);
  EXPECT_EQ(mesh.tets, original.tets);
  EXPECT_EQ(interface_faces(mesh), faces);
  // Bottom nodes (the pushed one and any neighbour that helps) slide along the bowl: the plane they
  // move in is within 2 x 5 degrees of their faces, which are within a few degrees of level.
  for (std::size_t i = 0; i < mesh.points.size(); ++i)
    if (original.points[i].z() < 1.0) {
      const Eigen::Vector3d d = mesh.points[i] - original.points[i];
      EXPECT_LE(std::abs(d.z()), std::sin(10.0 * M_PI / 180.0) * d.norm()) << "bottom node " << i;
    }
  const QualityReport after = compute_quality(mesh);
  EXPECT_NEAR(after.total.volume_mm3, before.total.volume_mm3, test::kRelativeRoundoff * before.total.volume_mm3);
  EXPECT_EQ(check_conformity(mesh).inverted_tets, 0u);
  std::cout << "[ smooth   ] bowl: min dihedral " << before.total.min_dihedral_deg << " -> "
            << after.total.min_dihedral_deg << " deg, node slid " << moved.norm() << " mm\n";
  EXPECT_GE(after.total.min_dihedral_deg, 10.0);
}

// The box's bottom is a spherical cap (radius 12 mm, centre above the box: face normals up to
// ~28 degrees from vertical, ~14 degrees apart around the middle node), and its middle bottom node
// is pushed along the sphere until its tets are slivers. Neither exactly-planar nor 5-degree
// near-planar smoothing can move it; with a projector onto the sphere (the reference surface of
// the box's boundary) it moves over the sphere: every node that was on the sphere still is, to
// round-off, and the worst angle recovers.
TEST(SliverSmoothing, MovesANodeOfACurvedBoundaryOverTheReferenceSurface) {
  const Eigen::Vector3d centre(4, 4, 12);
  const double radius = 12.0;
  auto onto_sphere = [&](Eigen::Vector3d x) { return Eigen::Vector3d(centre + radius * (x - centre).normalized()); };
  TetMesh mesh = test::box_mesh({0, 0, 0}, {8, 8, 4}, 4, 4, 2);
  for (auto& x : mesh.points)
    if (x.z() == 0.0) x.z() = centre.z() - std::sqrt(radius * radius - (x - centre).head<2>().squaredNorm());
  const int bottom = push_node(mesh, {4, 4, 0}, {0, 0, 0});
  Eigen::Vector3d& b = mesh.points[static_cast<std::size_t>(bottom)];
  b = onto_sphere(b + Eigen::Vector3d(1.8, 1.8, 0));
  ASSERT_EQ(check_conformity(mesh).inverted_tets, 0u);
  const QualityReport before = compute_quality(mesh);
  ASSERT_LT(before.total.min_dihedral_deg, 10.0);
  const TetMesh original = mesh;
  auto on_sphere = [&](const Eigen::Vector3d& x) {
    return std::abs((x - centre).norm() - radius) <= test::kRelativeRoundoff * radius;
  };

  TetMesh without = mesh;
  smooth_slivers(without, 15.0, /*near_planar_deg=*/5.0);
  EXPECT_EQ(without.points[static_cast<std::size_t>(bottom)], b);

  int projections = 0;
  const SurfaceProjector projector = [&](int p, int q, Eigen::Vector3d& x) {
    EXPECT_EQ(std::make_pair(p, q), std::make_pair(0, 1));  // the box's boundary is its only pair
    ++projections;
    x = onto_sphere(x);
    return true;
  };
  const SliverSmoothingResult r = smooth_slivers(mesh, 15.0, /*near_planar_deg=*/5.0, projector);
  EXPECT_GT(projections, 0);
  EXPECT_GE(r.moved_on_surface, 1u);
  const Eigen::Vector3d moved = mesh.points[static_cast<std::size_t>(bottom)] - original.points[static_cast<std::size_t>(bottom)];
  EXPECT_GT(moved.norm(), 0.1);
  EXPECT_EQ(mesh.tets, original.tets);
  for (std::size_t i = 0; i < mesh.points.size(); ++i) {
    if (on_sphere(original.points[i])) {
      EXPECT_TRUE(on_sphere(mesh.points[i])) << "node " << i << " left the sphere";
    }
  }
  EXPECT_EQ(check_conformity(mesh).inverted_tets, 0u);
  const QualityReport after = compute_quality(mesh);
  std::cout << "[ smooth   ] cap: min dihedral " << before.total.min_dihedral_deg << " -> "
            << after.total.min_dihedral_deg << " deg, node moved " << moved.norm() << " mm over the sphere\n";
  EXPECT_GE(after.total.min_dihedral_deg, 10.0);
  TetMesh again = original;
  smooth_slivers(again, 15.0, 5.0, projector);
  EXPECT_EQ(again.points, mesh.points);  // deterministic
}

// A knife-edge fin of tissue (half-angle ~10 degrees): the node in the middle of its edge has
// boundary faces on both sides of the fin, whose unoriented normals are within ~20 degrees of each
// other but whose outward normals face away from each other. It is a fold, not a curved patch:
// moving it over the surface would cut the rim, so it is never offered to the projector.
TEST(SliverSmoothing, KeepsTheNodeOnTheRimOfAThinFinFixed) {
  const double h = 0.18;  // fin half-thickness at 1 mm from its edge
  std::vector<Eigen::Vector3d> points;
  for (int y = 0; y <= 2; ++y) {
    points.push_back({0, double(y), 0});   // 3y:     on the edge
    points.push_back({-1, double(y), h});  // 3y + 1: top
    points.push_back({-1, double(y), -h}); // 3y + 2: bottom
  }
  std::vector<std::array<int, 4>> tets;
  for (int y = 0; y < 2; ++y) {  // prism (e0 t0 b0 | e1 t1 b1) as three tets
    const int e0 = 3 * y, t0 = e0 + 1, b0 = e0 + 2, e1 = e0 + 3, t1 = e0 + 4, b1 = e0 + 5;
    tets.push_back({e0, t0, b0, e1});
    tets.push_back({t0, b0, e1, t1});
    tets.push_back({b0, e1, t1, b1});
  }
  TetMesh mesh = oriented_mesh(points, tets, {1, 1, 1, 1, 1, 1}, {"fin"});
  ASSERT_EQ(check_conformity(mesh).inverted_tets, 0u);
  ASSERT_LT(compute_quality(mesh).total.min_dihedral_deg, 30.0);
  int projections = 0;
  const SurfaceProjector projector = [&](int, int, Eigen::Vector3d&) {
    ++projections;
    return true;
  };
  const SliverSmoothingResult r = smooth_slivers(mesh, 30.0, 0.0, projector);
  EXPECT_EQ(projections, 0);
  EXPECT_EQ(r.moved_on_surface, 0u);
  EXPECT_EQ(mesh.points[3], Eigen::Vector3d(0, 1, 0));
}

namespace {

// A 4 x 4 mm slab of three layers on a 1 mm grid: 1 mm of tissue 2, a sheet of tissue 1 only
// `sheet_mm` thick, 1 mm of tissue 2. Every node of the sheet is on an interface and the sheet's
// tets are flat: no move within the interfaces' planes and no split inside one tissue repairs
// them.
TetMesh pinched_sheet(double sheet_mm) {
  TetMesh mesh = test::box_mesh({0, 0, 0}, {4, 4, 3}, 4, 4, 3);
  const double z[4] = {0.0, 1.0, 1.0 + sheet_mm, 2.0 + sheet_mm};
  for (auto& x : mesh.points) x.z() = z[static_cast<int>(std::lround(x.z()))];
  for (std::size_t t = 0; t < mesh.tets.size(); ++t) {
    double zc = 0;
    for (int v : mesh.tets[t]) zc += 0.25 * mesh.points[static_cast<std::size_t>(v)].z();
    mesh.tissue_ids[t] = zc > 1.0 && zc < 1.0 + sheet_mm ? 1 : 2;
  }
  mesh.tissue_names = {"sheet", "around"};
  return mesh;
}

}  // namespace

// The last resort moves the sheet's nodes off its interfaces, never further than the bound (a
// fraction of the node's mean edge), and lifts the sheet's tets over 10 degrees; without the
// bound nothing can move them off.
TEST(SliverSmoothing, MovesNodesOfAPinchedSheetOffItsInterfacesWithinTheBound) {
  TetMesh mesh = pinched_sheet(0.08);
  ASSERT_EQ(check_conformity(mesh).inverted_tets, 0u);
  const QualityReport before = compute_quality(mesh);
  ASSERT_LT(before.tissues[0].min_dihedral_deg, 10.0);
  const TetMesh original = mesh;

  TetMesh within = mesh;
  const SliverSmoothingResult kept = smooth_slivers(within, 10.0);
  EXPECT_EQ(kept.moved_off_surface, 0u);
  EXPECT_NEAR(compute_quality(within).tissues[0].volume_mm3, before.tissues[0].volume_mm3,
              test::kRelativeRoundoff * before.tissues[0].volume_mm3);
  EXPECT_LT(compute_quality(within).tissues[0].min_dihedral_deg, 10.0);

  const double ratio = 0.3;
  // Each node's bound is at most ratio times its longest edge.
  std::vector<double> longest(mesh.points.size(), 0.0);
  for (const auto& k : mesh.tets)
    for (int a : k)
      for (int b : k)
        longest[static_cast<std::size_t>(a)] = std::max(
            longest[static_cast<std::size_t>(a)],
            (mesh.points[static_cast<std::size_t>(a)] - mesh.points[static_cast<std::size_t>(b)]).norm());
  const SliverSmoothingResult r = smooth_slivers(mesh, 10.0, 0.0, {}, 4, ratio);
  EXPECT_GT(r.moved_off_surface, 0u);
  EXPECT_GT(r.max_offset_mm, 0.0);
  EXPECT_EQ(mesh.tets, original.tets);
  for (std::size_t i = 0; i < mesh.points.size(); ++i)
    EXPECT_LE((mesh.points[i] - original.points[i]).norm(), ratio * longest[i]) << "node " << i;
  EXPECT_EQ(check_conformity(mesh).inverted_tets, 0u);
  const QualityReport after = compute_quality(mesh);
  // The slab as a whole keeps its volume to within the largest offset times its outer area.
  EXPECT_NEAR(after.total.volume_mm3, before.total.volume_mm3, r.max_offset_mm * (2 * 16 + 4 * 4 * 2.08));
  std::cout << "[ smooth   ] pinched sheet: min dihedral " << before.tissues[0].min_dihedral_deg << " -> "
            << after.tissues[0].min_dihedral_deg << " deg, nodes moved off by at most " << r.max_offset_mm << " mm\n";
  EXPECT_GE(after.total.min_dihedral_deg, 10.0);
}

// repair_slivers runs the last resort only while a tet is under 10 degrees, and not at all with
// sliver_offset_edge_ratio 0.
TEST(SliverRepair, OffSurfaceMovesOnlyWhereTetsStayUnderTenDegrees) {
  Mesh3Optimisation options;
  std::vector<std::string> warnings;
  TetMesh sheet = pinched_sheet(0.08);
  const SliverRepair r = repair_slivers(sheet, options, warnings);
  EXPECT_GT(r.sliver_offsets.moved_off_surface, 0u);
  EXPECT_GT(compute_quality(sheet).total.min_dihedral_deg, compute_quality(pinched_sheet(0.08)).total.min_dihedral_deg);

  Mesh3Optimisation off = options;
  off.sliver_offset_edge_ratio = 0.0;
  TetMesh kept = pinched_sheet(0.08);
  EXPECT_EQ(repair_slivers(kept, off, warnings).sliver_offsets.moved_off_surface, 0u);

  TetMesh thick = pinched_sheet(1.0);  // a regular grid: nothing under 10 degrees
  const TetMesh before = thick;
  EXPECT_EQ(repair_slivers(thick, options, warnings).sliver_offsets.passes, 0u);
  EXPECT_EQ(thick.points, before.points);
}
