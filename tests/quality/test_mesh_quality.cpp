// Element quality: analytic shapes (regular, right-corner, sliver), invariances, and per-tissue
// aggregates on Kuhn-split cube grids whose angles, volumes and node counts are known exactly.
#include "quality/mesh_quality.h"

#include "core/errors.h"
#include "support/tolerances.h"

#include <gtest/gtest.h>
#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <random>

namespace tissuemesh {
namespace {

using test::kAngleDeg;
using test::kRelativeRoundoff;
using Eigen::Vector3d;

const double kRadToDeg = 180.0 / std::acos(-1.0);

// The Kuhn (Freudenthal) split of a cube into 6 tets along its main diagonal has the dihedral
// angles 90 (x3), 60 (x1) and 45 (x2) degrees in every tet, and radius ratio sqrt(3)/(1+sqrt(2)):
// circumradius sqrt(3)/2 (the cube's), inradius 3V/area = 0.5/(1+sqrt(2)) on the unit cube.
const double kKuhnRadiusRatio = std::sqrt(3.0) / (1.0 + std::sqrt(2.0));

TetShape shape_of(const std::array<Vector3d, 4>& p) { return tet_shape(p[0], p[1], p[2], p[3]); }

// An n^3 grid of cubes of edge `spacing` mm, each Kuhn-split into 6 positively oriented tets;
// tissue 1 where `in_first_tissue(tet centroid)`, else tissue 2.
TetMesh kuhn_grid(int n, double spacing,
                  const std::function<bool(const Vector3d&)>& in_first_tissue) {
  TetMesh mesh;
  mesh.tissue_names = {"fat", "gland"};
  const auto node = [n](int i, int j, int k) { return (k * (n + 1) + j) * (n + 1) + i; };
  for (int k = 0; k <= n; ++k)
    for (int j = 0; j <= n; ++j)
      for (int i = 0; i <= n; ++i) mesh.points.emplace_back(spacing * Vector3d(i, j, k));

  std::array<int, 3> axes{0, 1, 2};
  for (int k = 0; k < n; ++k) {
    for (int j = 0; j < n; ++j) {
      for (int i = 0; i < n; ++i) {
        std::sort(axes.begin(), axes.end());
        do {  // one tet per order in which the path from corner (i,j,k) steps along the axes
          std::array<int, 3> at{i, j, k};
          std::array<int, 4> tet;
          tet[0] = node(at[0], at[1], at[2]);
          for (int s = 0; s < 3; ++s) {
            ++at[axes[s]];
            tet[s + 1] = node(at[0], at[1], at[2]);
          }
          const auto& p = mesh.points;
          if (signed_tet_volume(p[tet[0]], p[tet[1]], p[tet[2]], p[tet[3]]) < 0) {
            std::swap(tet[2], tet[3]);
          }
          const Vector3d centroid = (p[tet[0]] + p[tet[1]] + p[tet[2]] + p[tet[3]]) / 4.0;
          mesh.tets.push_back(tet);
          mesh.tissue_ids.push_back(in_first_tissue(centroid) ? 1 : 2);
        } while (std::next_permutation(axes.begin(), axes.end()));
      }
    }
  }
  return mesh;
}

// Unit cube, 3 tets with x >= y in tissue 1 and 3 with y > x in tissue 2 (split by the plane x=y).
TetMesh kuhn_cube() {
  return kuhn_grid(1, 1.0, [](const Vector3d& c) { return c.x() >= c.y(); });
}

TEST(TetShape, RegularTetHasAllDihedralsAcosOneThirdAndRadiusRatioOne) {
  const TetShape s = shape_of({Vector3d(1, 1, 1), Vector3d(-1, 1, -1), Vector3d(1, -1, -1),
                               Vector3d(-1, -1, 1)});
  for (double angle : s.dihedral_deg) {
    EXPECT_NEAR(angle, std::acos(1.0 / 3.0) * kRadToDeg, kAngleDeg);  // 70.5288 degrees
  }
  EXPECT_NEAR(s.radius_ratio, 1.0, kRelativeRoundoff);
  EXPECT_NEAR(s.sicn, 1.0, kRelativeRoundoff);  // the map from the unit regular tet is a similarity
  // Circumradius a sqrt(6)/4 over edge a.
  EXPECT_NEAR(s.radius_edge_ratio, std::sqrt(6.0) / 4.0, kRelativeRoundoff);
  // Edge length sqrt(8): volume a^3 / (6 sqrt(2)) = 8/3; the node order above is positive.
  EXPECT_NEAR(s.volume_mm3, 8.0 / 3.0, kRelativeRoundoff);
}

TEST(TetShape, RightCornerTetHasRightAnglesAtTheCornerEdges) {
  const TetShape s = shape_of({Vector3d(0, 0, 0), Vector3d(1, 0, 0), Vector3d(0, 1, 0),
                               Vector3d(0, 0, 1)});
  // kTetEdges[0..2] are the edges at node 0, the corner; the other three meet the slanted face.
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(s.dihedral_deg[i], 90.0, kAngleDeg);
  for (int i = 3; i < 6; ++i) {
    EXPECT_NEAR(s.dihedral_deg[i], std::acos(1.0 / std::sqrt(3.0)) * kRadToDeg, kAngleDeg);
    EXPECT_NEAR(s.dihedral_deg[i], 54.7356103172, kAngleDeg);  // literal to 1e-10
  }
  // Inradius 3V/area with V = 1/6 and area 3/2 + sqrt(3)/2; circumradius sqrt(3)/2 (unit cube's).
  const double inradius = 0.5 / (1.5 + std::sqrt(3.0) / 2.0);
  EXPECT_NEAR(s.radius_ratio, 3.0 * inradius / (std::sqrt(3.0) / 2.0), kRelativeRoundoff);
  // A = W^-1 maps the unit regular tet (edge vectors W) onto this one. A A^T is the inverse of
  // the regular tet's edge Gram matrix (1 on the diagonal, 1/2 off it; eigenvalues 2, 1/2, 1/2),
  // so |A|_F^2 = 1/2 + 2 + 2, |A^-1|_F^2 = 3 and SICN = 3 / sqrt(27/2) = sqrt(2/3). Gmsh 4.8
  // prints 0.816497.
  EXPECT_NEAR(s.sicn, std::sqrt(2.0 / 3.0), kRelativeRoundoff);
  EXPECT_NEAR(s.radius_edge_ratio, std::sqrt(3.0) / 2.0, kRelativeRoundoff);  // shortest edge 1
  EXPECT_NEAR(s.volume_mm3, 1.0 / 6.0, kRelativeRoundoff);
}

// Sliver over the unit square with the diagonal corners alternately lifted by h: the four side
// edges have dihedral atan(2h sqrt(1+h^2)) -> 0, the two diagonals 180 - atan2(2 sqrt(2) h,
// 1 - 2h^2) -> 180; 6V = 2h, all faces have area sqrt(1+2h^2)/2, circumradius sqrt(1/2 + h^2/4).
struct SliverReference {
  double side_deg, diagonal_deg, radius_ratio;
};
SliverReference sliver_reference(double h) {
  const double inradius = 3.0 * (h / 3.0) / (2.0 * std::sqrt(1.0 + 2.0 * h * h));
  const double circumradius = std::sqrt(0.5 + h * h / 4.0);
  return {std::atan(2.0 * h * std::sqrt(1.0 + h * h)) * kRadToDeg,
          180.0 - std::atan2(2.0 * std::sqrt(2.0) * h, 1.0 - 2.0 * h * h) * kRadToDeg,
          3.0 * inradius / circumradius};
}
std::array<Vector3d, 4> sliver(double h) {
  return {Vector3d(0, 0, 0), Vector3d(1, 0, h), Vector3d(1, 1, 0), Vector3d(0, 1, h)};
}

TEST(TetShape, SliverHasAnglesNearZeroAndNearStraightAndRadiusRatioNearZero) {
  const double h = 1e-3;
  const TetShape s = shape_of(sliver(h));
  const SliverReference ref = sliver_reference(h);
  // Edges (0,2) and (1,3), kTetEdges[1] and [4], are the square's diagonals.
  for (int i : {0, 2, 3, 5}) EXPECT_NEAR(s.dihedral_deg[i], ref.side_deg, kAngleDeg);
  for (int i : {1, 4}) EXPECT_NEAR(s.dihedral_deg[i], ref.diagonal_deg, kAngleDeg);
  EXPECT_LT(*std::min_element(s.dihedral_deg.begin(), s.dihedral_deg.end()), 0.2);
  EXPECT_GT(*std::max_element(s.dihedral_deg.begin(), s.dihedral_deg.end()), 179.5);
  EXPECT_NEAR(s.radius_ratio, ref.radius_ratio, kRelativeRoundoff * ref.radius_ratio);
  EXPECT_LT(s.radius_ratio, 0.01);
  // The radius-edge ratio does not see the sliver: circumradius sqrt(1/2 + h^2/4) over the side
  // sqrt(1 + h^2), about 1/sqrt(2), well inside TetGen's usual bound of 2.
  EXPECT_NEAR(s.radius_edge_ratio, std::sqrt(0.5 + h * h / 4.0) / std::sqrt(1.0 + h * h), kRelativeRoundoff);
  EXPECT_NEAR(s.volume_mm3, 2.0 * h / 6.0, kRelativeRoundoff * h);
}

// acos(n1.n2 / |n1||n2|) would return exactly 0 here (the cosine rounds to 1). atan2 keeps the
// absolute error near 1e-16 rad, which on these exactly representable coordinates is also a
// small relative error of the 2e-9 rad angle.
TEST(TetShape, NearlyFlatSliverAnglesAreAccurate) {
  const double h = 1e-9;
  const TetShape s = shape_of(sliver(h));
  const SliverReference ref = sliver_reference(h);
  for (int i : {0, 2, 3, 5}) {
    EXPECT_NEAR(s.dihedral_deg[i], ref.side_deg, kRelativeRoundoff * ref.side_deg);
  }
  for (int i : {1, 4}) EXPECT_NEAR(s.dihedral_deg[i], ref.diagonal_deg, kAngleDeg);
  EXPECT_NEAR(s.radius_ratio, ref.radius_ratio, kRelativeRoundoff);  // ratio is O(1)-scaled
}

TEST(TetShape, FlatAndCollapsedTetsHaveRadiusRatioZero) {
  EXPECT_EQ(shape_of(sliver(0.0)).radius_ratio, 0.0);
  EXPECT_EQ(shape_of(sliver(0.0)).sicn, 0.0);
  EXPECT_EQ(shape_of(sliver(0.0)).radius_edge_ratio, std::numeric_limits<double>::infinity());
  const TetShape collapsed = shape_of({Vector3d(0, 0, 0), Vector3d(0, 0, 0), Vector3d(1, 0, 0),
                                       Vector3d(0, 1, 0)});
  EXPECT_EQ(collapsed.radius_ratio, 0.0);
  EXPECT_EQ(collapsed.sicn, 0.0);
  EXPECT_EQ(collapsed.radius_edge_ratio, std::numeric_limits<double>::infinity());
  EXPECT_EQ(collapsed.volume_mm3, 0.0);
}

TEST(TetShape, ShapeIsInvariantUnderRotationTranslationAndUniformScaling) {
  const std::array<Vector3d, 4> p{Vector3d(0.1, -0.2, 0.3), Vector3d(1.7, 0.1, -0.4),
                                  Vector3d(0.4, 1.3, 0.2), Vector3d(0.6, 0.5, 2.1)};
  const Eigen::Matrix3d rotation = Eigen::AngleAxisd(0.7, Vector3d(1, 2, 3).normalized()).matrix();
  const Vector3d shift(10.0, -20.0, 30.0);
  const double scale = 3.7;
  std::array<Vector3d, 4> q;
  for (int i = 0; i < 4; ++i) q[i] = scale * (rotation * p[i]) + shift;

  const TetShape a = shape_of(p), b = shape_of(q);
  for (int i = 0; i < 6; ++i) EXPECT_NEAR(a.dihedral_deg[i], b.dihedral_deg[i], kAngleDeg);
  EXPECT_NEAR(a.radius_ratio, b.radius_ratio, kRelativeRoundoff);
  EXPECT_NEAR(a.sicn, b.sicn, kRelativeRoundoff);
  EXPECT_NEAR(a.radius_edge_ratio, b.radius_edge_ratio, kRelativeRoundoff);
  EXPECT_NEAR(b.volume_mm3, scale * scale * scale * a.volume_mm3,
              kRelativeRoundoff * std::abs(b.volume_mm3));
}

TEST(TetShape, InvertedTetHasTheSameShapeAndNegativeVolume) {
  const std::array<Vector3d, 4> p{Vector3d(0.1, -0.2, 0.3), Vector3d(1.7, 0.1, -0.4),
                                  Vector3d(0.4, 1.3, 0.2), Vector3d(0.6, 0.5, 2.1)};
  const TetShape a = shape_of(p);
  const TetShape b = shape_of({p[0], p[1], p[3], p[2]});  // swapping c, d swaps edges 0-2, 0-3
  ASSERT_GT(a.volume_mm3, 0.0);
  EXPECT_NEAR(b.volume_mm3, -a.volume_mm3, kRelativeRoundoff * a.volume_mm3);
  EXPECT_NEAR(b.radius_ratio, a.radius_ratio, kRelativeRoundoff);
  EXPECT_NEAR(b.sicn, -a.sicn, kRelativeRoundoff);  // SICN is the one signed shape measure
  EXPECT_NEAR(b.radius_edge_ratio, a.radius_edge_ratio, kRelativeRoundoff);
  EXPECT_GT(a.sicn, 0.0);
  const std::array<int, 6> swapped_edge{0, 2, 1, 4, 3, 5};  // kTetEdges index after c <-> d
  for (int i = 0; i < 6; ++i) {
    EXPECT_NEAR(b.dihedral_deg[swapped_edge[i]], a.dihedral_deg[i], kAngleDeg);
  }
}

TEST(TetShape, VolumeAndMinDihedralAreTetShapesBitForBit) {
  // The sliver repairs use tet_volume_and_min_dihedral instead of tet_shape for speed; their
  // decisions (and so the meshes) stay the same only if both give the same doubles. Random tets,
  // each also inverted, made nearly flat and given a zero-length edge, so that the smallest angle
  // sits at every edge in turn. Mutation check: a minimum over edges 1-5 only fails here. (Both
  // share TetFrame, so this pins their agreement, not tet_shape's values: the analytic tests above
  // do that.)
  std::mt19937 random(7);  // the same sequence on every platform
  std::uniform_real_distribution<double> uniform(-10.0, 10.0);
  auto coordinate = [&] { return uniform(random); };
  std::array<int, 6> smallest_at{};
  for (int k = 0; k < 4000; ++k) {
    std::array<Vector3d, 4> p;
    for (Vector3d& x : p) x = Vector3d(coordinate(), coordinate(), coordinate());
    if (k % 4 == 1) std::swap(p[2], p[3]);                              // inverted
    if (k % 4 == 2) p[3] = (p[0] + p[1] + p[2]) / 3.0 + 1e-9 * (p[3] - p[0]);  // nearly flat
    if (k % 4 == 3) p[1] = p[0];                                        // a zero-length edge
    const TetShape s = shape_of(p);
    const TetVolumeAndAngle f = tet_volume_and_min_dihedral(p[0], p[1], p[2], p[3]);
    const auto lowest = std::min_element(s.dihedral_deg.begin(), s.dihedral_deg.end());
    ++smallest_at[static_cast<std::size_t>(lowest - s.dihedral_deg.begin())];
    EXPECT_EQ(f.volume_mm3, s.volume_mm3) << "tet " << k;
    EXPECT_EQ(f.min_dihedral_deg, *lowest) << "tet " << k;
  }
  for (int count : smallest_at) EXPECT_GT(count, 0);
}

TEST(MeshQuality, KuhnCubeSplitsItsUnitVolumeEvenlyBetweenTwoTissues) {
  const QualityReport r = compute_quality(kuhn_cube());
  ASSERT_EQ(r.tissues.size(), 2u);
  EXPECT_NEAR(r.total.volume_mm3, 1.0, kRelativeRoundoff);
  for (const TissueQuality& q : r.tissues) {
    EXPECT_EQ(q.tets, 3u);
    EXPECT_NEAR(q.volume_mm3, 0.5, kRelativeRoundoff);
    EXPECT_EQ(q.vertices, 6u);  // the 8 corners but the two off the plane x = y on the other side
    EXPECT_TRUE(std::isnan(q.reference_volume_mm3));
    EXPECT_TRUE(std::isnan(q.volume_error_rel));
  }
  EXPECT_EQ(r.tissues[0].name, "fat");
  EXPECT_EQ(r.tissues[1].id, 2);
  EXPECT_EQ(r.total.tets, 6u);
  EXPECT_EQ(r.total.vertices, 8u);
  EXPECT_EQ(r.total.id, 0);
}

// 10^3 cubes of 2 mm, 6000 tets, tissue 1 where x < 10 mm.
TetMesh split_grid() {
  return kuhn_grid(10, 2.0, [](const Vector3d& c) { return c.x() < 10.0; });
}

TEST(MeshQuality, StructuredGridHistogramHoldsSixAnglesPerTetAtTheirExactBins) {
  const QualityReport r = compute_quality(split_grid());
  const std::size_t tets = 6000;
  ASSERT_EQ(r.total.tets, tets);
  const auto& counts = r.total.dihedral_histogram.counts;
  ASSERT_EQ(counts.size(), 36u);
  EXPECT_EQ(r.total.dihedral_histogram.bin_width_deg, 5.0);
  std::size_t sum = 0;
  for (std::size_t c : counts) sum += c;
  EXPECT_EQ(sum, 6 * tets);
  // Bins are [5i, 5i+5): 45 -> bin 9, 60 -> bin 12, 90 -> bin 18; nothing elsewhere.
  EXPECT_EQ(counts[9], 2 * tets);
  EXPECT_EQ(counts[12], tets);
  EXPECT_EQ(counts[18], 3 * tets);
  EXPECT_NEAR(r.total.min_dihedral_deg, 45.0, kAngleDeg);
  EXPECT_NEAR(r.total.max_dihedral_deg, 90.0, kAngleDeg);
  EXPECT_EQ(r.total.tets_below_10deg, 0u);
  EXPECT_EQ(r.total.tets_below_5deg, 0u);
  EXPECT_NEAR(r.total.min_radius_ratio, kKuhnRadiusRatio, kRelativeRoundoff);
  EXPECT_NEAR(r.total.mean_radius_ratio, kKuhnRadiusRatio, kRelativeRoundoff);
  // Every Kuhn tet has the cube's circumsphere (radius sqrt(3)/2 of the 2 mm edge) and the cube
  // edge as its shortest edge.
  EXPECT_NEAR(r.total.max_radius_edge_ratio, std::sqrt(3.0) / 2.0, kRelativeRoundoff);
  EXPECT_EQ(r.total.tets_radius_edge_above_2, 0u);
  for (const TissueQuality& q : r.tissues) {
    std::size_t tissue_sum = 0;
    for (std::size_t c : q.dihedral_histogram.counts) tissue_sum += c;
    EXPECT_EQ(tissue_sum, 6 * q.tets);
  }
}

TEST(MeshQuality, StructuredGridTissuesHaveExactVolumesAndNodeCounts) {
  const QualityReport r = compute_quality(split_grid());
  // 20 mm cube cut at x = 10 mm; each half has 6 x 11 x 11 nodes, sharing the 11 x 11 of the cut.
  EXPECT_NEAR(r.total.volume_mm3, 8000.0, kRelativeRoundoff * 8000.0);
  EXPECT_EQ(r.total.vertices, 11u * 11u * 11u);
  for (const TissueQuality& q : r.tissues) {
    EXPECT_EQ(q.tets, 3000u);
    EXPECT_NEAR(q.volume_mm3, 4000.0, kRelativeRoundoff * 4000.0);
    EXPECT_EQ(q.vertices, 6u * 11u * 11u);
  }
}

TEST(MeshQuality, TetsWithSmallAnglesAreCountedBelowTheirThresholds) {
  TetMesh mesh = kuhn_cube();
  // Three slivers in tissue 2, away from the cube, with smallest angles in (0,5), [5,10), [10,15).
  struct Case { double h, lo_deg, hi_deg; };
  for (const Case c : {Case{1e-3, 0, 5}, Case{0.0633, 5, 10}, Case{0.1, 10, 15}}) {
    ASSERT_GT(sliver_reference(c.h).side_deg, c.lo_deg);
    ASSERT_LT(sliver_reference(c.h).side_deg, c.hi_deg);
    const int base = static_cast<int>(mesh.points.size());
    for (const Vector3d& p : sliver(c.h)) mesh.points.push_back(p + Vector3d(5, 5, 5));
    mesh.tets.push_back({base, base + 1, base + 2, base + 3});
    mesh.tissue_ids.push_back(2);
  }
  const QualityReport r = compute_quality(mesh);
  EXPECT_EQ(r.tissues[0].tets_below_10deg, 0u);
  EXPECT_EQ(r.tissues[1].tets_below_10deg, 2u);
  EXPECT_EQ(r.tissues[1].tets_below_5deg, 1u);
  EXPECT_EQ(r.total.tets_below_10deg, 2u);
  EXPECT_NEAR(r.tissues[1].min_dihedral_deg, sliver_reference(1e-3).side_deg, kAngleDeg);
  EXPECT_NEAR(r.total.max_dihedral_deg, sliver_reference(1e-3).diagonal_deg, kAngleDeg);
  EXPECT_NEAR(r.tissues[0].mean_radius_ratio, kKuhnRadiusRatio, kRelativeRoundoff);
  EXPECT_NEAR(r.tissues[1].min_radius_ratio, sliver_reference(1e-3).radius_ratio,
              kRelativeRoundoff);
}

TEST(MeshQuality, TetsWithAShortEdgeAreCountedAboveRadiusEdgeTwo) {
  TetMesh mesh = kuhn_cube();
  // Caps over the right-angled unit triangle, apex at height e over its corner: circumcentre
  // (1/2, 1/2, e/2), so R / e = sqrt(1/2 + e^2/4) / e, the shortest edge being e (< 1).
  const auto ratio = [](double e) { return std::sqrt(0.5 + e * e / 4.0) / e; };
  for (double e : {0.5, 0.3, 0.1}) {
    const int base = static_cast<int>(mesh.points.size());
    for (const Vector3d& p : {Vector3d(0, 0, 0), Vector3d(1, 0, 0), Vector3d(0, 1, 0), Vector3d(0, 0, e)})
      mesh.points.push_back(p + Vector3d(5, 5, 5));
    mesh.tets.push_back({base, base + 1, base + 2, base + 3});
    mesh.tissue_ids.push_back(1);
  }
  ASSERT_LT(ratio(0.5), 2.0);  // 1.5
  ASSERT_GT(ratio(0.3), 2.0);  // 2.4
  const QualityReport r = compute_quality(mesh);
  EXPECT_EQ(r.tissues[0].tets_radius_edge_above_2, 2u);
  EXPECT_EQ(r.tissues[1].tets_radius_edge_above_2, 0u);
  EXPECT_EQ(r.total.tets_radius_edge_above_2, 2u);
  EXPECT_NEAR(r.tissues[0].max_radius_edge_ratio, ratio(0.1), kRelativeRoundoff * ratio(0.1));
  EXPECT_NEAR(r.tissues[1].max_radius_edge_ratio, std::sqrt(3.0) / 2.0, kRelativeRoundoff);
}

TEST(MeshQuality, ReferenceVolumesGiveRelativeVolumeErrors) {
  // Tissue 1 meshes 4000 mm^3 against a reference of 5000: error -20 %; tissue 2 unknown.
  const QualityReport partial = compute_quality(split_grid(), {{1, 5000.0}});
  EXPECT_EQ(partial.tissues[0].reference_volume_mm3, 5000.0);
  EXPECT_NEAR(partial.tissues[0].volume_error_rel, -0.2, kRelativeRoundoff);
  EXPECT_TRUE(std::isnan(partial.tissues[1].volume_error_rel));
  EXPECT_TRUE(std::isnan(partial.total.reference_volume_mm3));  // not all tissues known
  EXPECT_TRUE(std::isnan(partial.total.volume_error_rel));

  const QualityReport full = compute_quality(split_grid(), {{1, 5000.0}, {2, 3200.0}});
  EXPECT_NEAR(full.tissues[1].volume_error_rel, 0.25, kRelativeRoundoff);
  EXPECT_EQ(full.total.reference_volume_mm3, 8200.0);
  EXPECT_NEAR(full.total.volume_error_rel, 8000.0 / 8200.0 - 1.0, kRelativeRoundoff);
}

TEST(MeshQuality, RejectsReferencesForUnknownTissuesOrNonPositiveVolumes) {
  const TetMesh mesh = kuhn_cube();
  EXPECT_THROW(compute_quality(mesh, {{3, 1.0}}), InputError);
  EXPECT_THROW(compute_quality(mesh, {{0, 1.0}}), InputError);
  EXPECT_THROW(compute_quality(mesh, {{1, 0.0}}), InputError);
  EXPECT_THROW(compute_quality(mesh, {{1, std::nan("")}}), InputError);
  TetMesh broken = mesh;
  broken.tissue_ids[0] = 7;
  EXPECT_THROW(compute_quality(broken), InputError);
}

TEST(MeshQuality, TissueWithoutTetsIsReportedWithUnknownShape) {
  TetMesh mesh = kuhn_cube();
  mesh.tissue_names.push_back("tumor");
  const QualityReport r = compute_quality(mesh, {{3, 2.0}});
  ASSERT_EQ(r.tissues.size(), 3u);
  const TissueQuality& tumor = r.tissues[2];
  EXPECT_EQ(tumor.name, "tumor");
  EXPECT_EQ(tumor.tets, 0u);
  EXPECT_EQ(tumor.vertices, 0u);
  EXPECT_EQ(tumor.volume_mm3, 0.0);
  EXPECT_EQ(tumor.volume_error_rel, -1.0);  // the whole reference volume is lost
  EXPECT_TRUE(std::isnan(tumor.min_dihedral_deg));
  EXPECT_TRUE(std::isnan(tumor.mean_radius_ratio));
  const nlohmann::json j = to_json(r);
  EXPECT_TRUE(j["tissues"][2]["min_dihedral_deg"].is_null());
  EXPECT_EQ(j["tissues"][2]["volume_error_rel"].get<double>(), -1.0);
}

TEST(MeshQuality, JsonRoundTripKeepsEveryKeyAndValue) {
  const QualityReport r = compute_quality(split_grid(), {{1, 5000.0}});
  const nlohmann::json j = nlohmann::json::parse(to_json(r).dump());
  ASSERT_EQ(j["tissues"].size(), 2u);
  const char* keys[] = {"name", "id", "tets", "vertices", "volume_mm3", "reference_volume_mm3",
                        "volume_error_rel", "min_dihedral_deg", "max_dihedral_deg",
                        "tets_below_10deg", "tets_below_5deg", "min_radius_ratio",
                        "mean_radius_ratio", "min_sicn", "max_radius_edge_ratio",
                        "tets_radius_edge_above_2", "dihedral_histogram"};
  for (const nlohmann::json& t : {j["tissues"][0], j["tissues"][1], j["total"]}) {
    for (const char* key : keys) EXPECT_TRUE(t.contains(key)) << key;
    EXPECT_EQ(t["dihedral_histogram"]["counts"].size(), 36u);
    EXPECT_EQ(t["dihedral_histogram"]["angles_per_tet"], 6);
  }
  EXPECT_EQ(j["tissues"][0]["name"], "fat");
  EXPECT_EQ(j["tissues"][1]["tets"], 3000);
  EXPECT_EQ(j["tissues"][0]["volume_error_rel"].get<double>(), r.tissues[0].volume_error_rel);
  EXPECT_EQ(j["total"]["volume_mm3"].get<double>(), r.total.volume_mm3);
  EXPECT_TRUE(j["tissues"][1]["reference_volume_mm3"].is_null());
  EXPECT_EQ(j["total"]["dihedral_histogram"]["counts"][18], 3 * 6000);
}

TEST(MeshQuality, TableNamesEveryTissueWithUnitsInTheHeader) {
  const QualityReport r = compute_quality(split_grid(), {{1, 5000.0}});
  const std::string table = format_quality_table(r);
  for (const char* text : {"tissue", "volume[mm^3]", "min[deg]", "err[%]", "fat", "gland",
                           "all tissues", "-20.00", "4000.00", "45.00", "90.00"}) {
    EXPECT_NE(table.find(text), std::string::npos) << text << "\n" << table;
  }
  EXPECT_EQ(table.back(), '\n');
}

}  // namespace
}  // namespace tissuemesh
