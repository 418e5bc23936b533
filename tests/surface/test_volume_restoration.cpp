// Volume restoration of a remeshed surface (surface/volume_restoration.h): a coarse remesh of the
// test complexes loses volume; the patch offsets give every tissue its reference volume back (here
// the extracted surface's) to the tolerance, the surface stays valid and intersection free, its
// smallest triangle angle does not drop, junction vertices stay where they are, and a bad
// reference is an input error.
#include "core/errors.h"
#include "surface/surface_checks.h"
#include "surface/surface_quality.h"
#include "surface/volume_restoration.h"
#include "support/complex_meshes.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <iostream>
#include <tuple>

using namespace tissuemesh;
using namespace tissuemesh::test;

namespace {

// `image` (regions 1..`regions`) remeshed to `vertices` must leave tissue 1 under `lost_below`
// of its extracted volume (or the test means nothing); restored, every tissue is within 1e-3 of
// its extracted volume, the surface valid, its smallest angle not lowered. `what` names tissue 1.
void expect_restored_from_a_coarse_remesh(const LabelImage& image, int regions, int vertices, double lost_below,
                                          const char* what) {
  const std::map<int, double> reference = enclosed_volumes(extract(image, regions).surface);
  TriSurface s = remeshed(image, regions, vertices).surface;
  ASSERT_TRUE(check_surface(s).valid());
  const std::map<int, double> before = enclosed_volumes(s);
  ASSERT_LT(before.at(1) / reference.at(1), lost_below) << "the coarse " << what << " must lose volume for the test to mean something";
  const double min_angle = surface_quality(s).min_angle_deg;
  const VolumeRestoration r = restore_volumes(s, reference);
  std::cout << "[ surface  ] " << what << " " << before.at(1) / reference.at(1) - 1.0 << " -> "
            << r.volume_after_mm3.at(1) / reference.at(1) - 1.0 << " in " << r.rounds << " rounds, "
            << r.frozen_vertices << " held, largest move " << r.max_offset_mm << " mm\n";
  for (const auto& [id, v] : reference) EXPECT_NEAR(r.volume_after_mm3.at(id) / v, 1.0, 1e-3) << "tissue " << id;
  EXPECT_TRUE(check_surface(s).valid());
  EXPECT_GE(surface_quality(s).min_angle_deg, min_angle);
}

}  // namespace

TEST(VolumeRestoration, RemeshedComplexesGetTheirVolumesBack) {
  for (const auto& [image, tissues, budget] :
       {std::tuple{nested_spheres(), 2, 150}, std::tuple{three_boxes(), 3, 200}}) {
    const std::map<int, double> reference = enclosed_volumes(extract(image, tissues).surface);
    TriSurface s = remeshed(image, tissues, budget).surface;
    const std::map<int, double> before = enclosed_volumes(s);
    double worst_before = 0.0;
    for (const auto& [id, v] : reference) worst_before = std::max(worst_before, std::abs(before.at(id) / v - 1.0));
    ASSERT_GT(worst_before, 1e-3) << "the coarse remesh must lose volume for the test to mean something";
    const double min_angle = surface_quality(s).min_angle_deg;
    const TriSurface original = s;

    const VolumeRestoration r = restore_volumes(s, reference);
    EXPECT_GE(r.rounds, 1);
    EXPECT_FALSE(r.stopped_early);
    for (const auto& [id, v] : reference) {
      EXPECT_NEAR(r.volume_after_mm3.at(id) / v, 1.0, 1e-4) << "tissue " << id;
      EXPECT_NEAR(enclosed_volumes(s).at(id), r.volume_after_mm3.at(id), 1e-9 * v);
    }
    EXPECT_TRUE(check_surface(s).valid());
    EXPECT_GE(surface_quality(s).min_angle_deg, min_angle);
    EXPECT_EQ(s.triangles, original.triangles);
    for (const auto& line : s.junctions)
      for (int v : line) EXPECT_EQ(s.points[v], original.points[v]);
    EXPECT_GT(r.max_offset_mm, 0.0);
    EXPECT_LT(r.max_offset_mm, 1.0);  // a small correction, not a new surface
  }
}

TEST(VolumeRestoration, BadReferenceIsAnInputError) {
  TriSurface s = remeshed(nested_spheres(), 2, 150).surface;
  EXPECT_THROW(restore_volumes(s, {{3, 100.0}}), InputError);
  EXPECT_THROW(restore_volumes(s, {{1, -1.0}}), InputError);
}

// Two balls 0.5 mm apart in a third tissue: asked for 45 % more volume, ball 1 cannot grow where
// it faces ball 2 without the two surfaces crossing. The vertices there are held and the rest of
// ball 1 grows instead: the volumes are met, the surface stays intersection free.
TEST(VolumeRestoration, ATightSpotIsHeldWhileTheRestMoves) {
  const LabelImage image = make_image({72, 20, 20}, {0.5, 1.0, 1.0}, [](int i, int j, int k) {
    if (i < 2 || i >= 70 || j < 1 || j >= 19 || k < 1 || k >= 19) return 0;
    const Eigen::Vector3d p(0.5 * (i + 0.5), j + 0.5, k + 0.5);
    if ((p - Eigen::Vector3d(10.5, 10.0, 10.0)).norm() < 6.0) return 1;
    if ((p - Eigen::Vector3d(23.0, 10.0, 10.0)).norm() < 6.0) return 2;
    return 3;
  });
  TriSurface s = remeshed(image, 3, 500).surface;
  ASSERT_TRUE(check_surface(s).valid());
  const std::map<int, double> before = enclosed_volumes(s);
  const std::map<int, double> reference = {{1, 1.45 * before.at(1)}, {2, before.at(2)}, {3, before.at(3)}};
  const double min_angle = surface_quality(s).min_angle_deg;

  const VolumeRestoration r = restore_volumes(s, reference);
  std::cout << "[ surface  ] " << r.rounds << " rounds, " << r.frozen_vertices << " vertices held, largest move "
            << r.max_offset_mm << " mm; ball 1 " << r.volume_after_mm3.at(1) / reference.at(1) - 1.0 << "\n";
  EXPECT_GT(r.frozen_vertices, 0u);
  for (const auto& [id, v] : reference) EXPECT_NEAR(r.volume_after_mm3.at(id) / v, 1.0, 1e-3) << "tissue " << id;
  EXPECT_TRUE(check_surface(s).valid());
  EXPECT_GE(surface_quality(s).min_angle_deg, min_angle);
}

// Two touching balls in a box of a third tissue, no vertex allowed to move more than 0.3 mm: ball
// 1, asked for 10 % more (about 0.2 mm of radius), can get it; ball 2, asked for three times its
// volume, cannot. Once a round cannot move ball 2 (its moves at the bound), its large deficit
// would dominate the least-squares offsets of the patches it shares and trade ball 1's and the
// box's small ones for nothing; it is released instead (it no longer constrains the offsets and
// its vertices stay), and the others reach their volumes.
TEST(VolumeRestoration, ATissueTheOffsetsCannotMoveIsReleasedAndTheRestIsRestored) {
  const LabelImage image = make_image({60, 20, 20}, {0.5, 1.0, 1.0}, [](int i, int j, int k) {
    if (i < 2 || i >= 58 || j < 1 || j >= 19 || k < 1 || k >= 19) return 0;
    const Eigen::Vector3d p(0.5 * (i + 0.5), j + 0.5, k + 0.5);
    if ((p - Eigen::Vector3d(9.0, 10.0, 10.0)).norm() < 6.0) return 1;
    if ((p - Eigen::Vector3d(20.0, 10.0, 10.0)).norm() < 6.0) return 2;
    return 3;
  });
  TriSurface s = remeshed(image, 3, 500).surface;
  ASSERT_TRUE(check_surface(s).valid());
  const TriSurface original = s;
  const std::map<int, double> before = enclosed_volumes(s);
  const std::map<int, double> reference = {{1, 1.1 * before.at(1)}, {2, 3.0 * before.at(2)}, {3, before.at(3)}};
  const VolumeRestoration r = restore_volumes(s, reference, 1e-4, 8, {}, 0.3);
  std::cout << "[ surface  ] " << r.rounds << " rounds, released";
  for (int id : r.released) std::cout << " " << id;
  std::cout << "; ball 1 " << r.volume_after_mm3.at(1) / reference.at(1) - 1.0 << ", box "
            << r.volume_after_mm3.at(3) / reference.at(3) - 1.0 << ", ball 2 " << r.volume_after_mm3.at(2) / before.at(2)
            << " times\n";
  ASSERT_FALSE(r.released.empty());
  EXPECT_EQ(r.released.front(), 2);
  EXPECT_NEAR(r.volume_after_mm3.at(1) / reference.at(1), 1.0, 1e-3);
  EXPECT_NEAR(r.volume_after_mm3.at(3) / reference.at(3), 1.0, 1e-3);
  EXPECT_NEAR(r.volume_after_mm3.at(2) / before.at(2), 1.0, 1e-12);  // released at once: its vertices stay
  double largest = 0.0;
  for (std::size_t v = 0; v < s.points.size(); ++v) largest = std::max(largest, (s.points[v] - original.points[v]).norm());
  EXPECT_LE(largest, 0.3 + 1e-12);
  EXPECT_TRUE(check_surface(s).valid());
}

// A marker clip: a ball five voxels across inside a block of another tissue, remeshed so coarsely
// that it keeps a handful of vertices and loses a third of its volume. Every vertex of such a ball
// bends by far more than a sheet's rim may; as a closed island it is still inflated back to its
// voxel volume.
TEST(VolumeRestoration, ACoarseClosedIslandIsInflatedBack) {
  const LabelImage image = make_image({24, 24, 24}, {0.5, 0.5, 0.5}, [](int i, int j, int k) {
    if (i < 2 || i >= 22 || j < 2 || j >= 22 || k < 2 || k >= 22) return 0;
    const int di = i - 12, dj = j - 12, dk = k - 12;
    return di * di + dj * dj + dk * dk <= 4 ? 1 : 2;
  });
  expect_restored_from_a_coarse_remesh(image, 2, 120, 0.8, "ball");
}

// A vessel: a tube four voxels across in a block of tissue 2, running into tissue 3 (so its patch
// ends at a junction loop), remeshed so coarsely that a handful of vertices go round it and the
// tube loses a third of its volume. Its vertices bend by more than 40 degrees, and the restoration
// must still move them (held at 40 degrees, the tube keeps its loss; vessel trees of real maps
// are made of such tubes).
TEST(VolumeRestoration, ACoarseTubeAtAJunctionIsInflatedBack) {
  const LabelImage image = make_image({64, 16, 16}, {0.5, 0.5, 0.5}, [](int i, int j, int k) {
    if (i < 1 || i >= 63 || j < 1 || j >= 15 || k < 1 || k >= 15) return 0;
    const double dj = j - 7.5, dk = k - 7.5;
    if (i >= 6 && dj * dj + dk * dk <= 4.0) return 1;
    return i >= 44 ? 3 : 2;
  });
  expect_restored_from_a_coarse_remesh(image, 3, 400, 0.97, "tube");
}

// Vessels thinner than the remeshed edges: three tubes three voxels across in tissue 2, running
// into tissue 3, remeshed so coarsely that they lose almost half their volume. The offset solved
// for them is larger than many of their vertices may move in a round (their shortest edge): the
// moves are clipped there and the rounds go on (holding those vertices instead raised the offset
// of the others, until every tube vertex was held and the tubes kept their loss).
TEST(VolumeRestoration, ThinTubesWhoseMovesAreClippedAreInflatedBackOverRounds) {
  const LabelImage image = make_image({64, 20, 20}, {0.5, 0.5, 0.5}, [](int i, int j, int k) {
    if (i < 1 || i >= 63 || j < 1 || j >= 19 || k < 1 || k >= 19) return 0;
    for (const auto& c : {std::array<double, 2>{6.5, 6.5}, std::array<double, 2>{12.5, 7.5}, std::array<double, 2>{9.5, 13.0}}) {
      const double dj = j - c[0], dk = k - c[1];
      if (i >= 6 && dj * dj + dk * dk <= 2.0) return 1;
    }
    return i >= 44 ? 3 : 2;
  });
  expect_restored_from_a_coarse_remesh(image, 3, 1200, 0.7, "tubes");
}
