// Multi-material surface extraction (docs/surface-pipeline.md, "Multi-material surface
// extraction"): voxel repair, shared interfaces, junction curves,
// closedness/orientation/intersections, volumes, determinism, on small generated images.
#include "core/errors.h"
#include "core/surface_vtp.h"
#include "image/label_repair.h"
#include "image/phantom.h"
#include "surface/surface_checks.h"
#include "surface/surface_extraction.h"
#include "surface/surface_quality.h"
#include "support/surface_images.h"
#include "support/surface_reports.h"
#include "support/tolerances.h"

#include <gtest/gtest.h>
#include <vtkCellData.h>
#include <vtkIdList.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkXMLPolyDataReader.h>

#include <cmath>
#include <cstdint>
#include <functional>
#include <random>
#include <set>

using namespace tissuemesh;
using namespace tissuemesh::test;

namespace {

double voxel_volume(const LabelImage& img, int id) {
  double n = 0;
  for (int l : img.labels) n += l == id;
  return n * img.voxel_volume();
}

}  // namespace

TEST(SurfaceExtraction, NestedSpheresAreClosedOrientedAndKeepTheirVolume) {
  const LabelImage img = nested_spheres();
  const SurfaceExtraction ex = extract(img, 2);
  const TriSurface& s = ex.surface;
  ASSERT_NO_THROW(s.validate("nested spheres"));
  const SurfaceCheckReport checks = check_surface(s);
  EXPECT_TRUE(checks.valid());
  EXPECT_EQ(checks.duplicate_triangles, 0u);
  ASSERT_EQ(checks.tissues.size(), 2u);
  for (const auto& t : checks.tissues) {
    EXPECT_TRUE(t.closed_and_oriented()) << t.name;
    EXPECT_EQ(t.intersecting_pairs, 0) << t.name;
    // Outward orientation gives a positive enclosed volume close to the voxel volume (the surface
    // stays in the half-voxel band and Taubin relaxation does not shrink).
    EXPECT_NEAR(t.volume_mm3, voxel_volume(img, t.tissue_id), kExtractedSurfaceVolumeRel * voxel_volume(img, t.tissue_id))
        << t.name;
  }
  // Only the two nested interfaces exist, so no curve where three regions meet.
  std::set<std::array<int, 2>> patches(s.labels.begin(), s.labels.end());
  EXPECT_EQ(patches, (std::set<std::array<int, 2>>{{0, 1}, {1, 2}}));
  EXPECT_TRUE(s.junctions.empty());
  // The inner sphere's boundary is the whole (1|2) interface: shared by both tissues, stored once.
  std::size_t shared = 0;
  for (const auto& pq : s.labels) shared += pq == std::array<int, 2>{1, 2};
  EXPECT_EQ(checks.tissues[1].triangles, shared);
  EXPECT_EQ(checks.tissues[0].triangles, s.triangles.size());
  // Relaxation smooths the staircase: far better triangles than the voxel corners give.
  EXPECT_GT(surface_quality(s).q_average, surface_quality(extract(img, 2, 0).surface).q_average);
}

TEST(SurfaceExtraction, TripleJunctionStaysOnItsLineAndFlatInterfacesStayFlat) {
  const LabelImage img = three_boxes();
  const SurfaceExtraction ex = extract(img, 3);
  const TriSurface& s = ex.surface;
  const SurfaceCheckReport checks = check_surface(s);
  EXPECT_TRUE(checks.valid());
  EXPECT_GT(checks.junction_edges, 0u);
  EXPECT_EQ(checks.junction_edges_off_junction, 0u);
  EXPECT_GT(ex.corner_vertices, 0u);  // where 0, 1, 2, 3 meet, curves meet
  // The 1|2|3 junction: vertices with physical x = origin + 14.5, y = origin + 14.5 exactly.
  const double x0 = img.origin[0] + 14.5, y0 = img.origin[1] + 14.5;
  bool found = false;
  for (const auto& line : s.junctions) {
    const auto on_line = [&](int v) {
      return std::abs(s.points[v][0] - x0) < kConstrainedCoordinateMm && std::abs(s.points[v][1] - y0) < kConstrainedCoordinateMm;
    };
    if (line.size() < 3 || !on_line(line[1])) continue;
    found = true;
    for (int v : line) EXPECT_TRUE(on_line(v)) << "junction vertex " << v << " left the 1|2|3 line";
  }
  EXPECT_TRUE(found);
  // The flat 1|2 interface: every vertex stays in the plane x = x0, and it is stored once.
  std::size_t n12 = 0;
  for (std::size_t t = 0; t < s.triangles.size(); ++t) {
    if (s.labels[t] != std::array<int, 2>{1, 2}) continue;
    ++n12;
    for (int v : s.triangles[t]) EXPECT_NEAR(s.points[v][0], x0, kConstrainedCoordinateMm);
  }
  EXPECT_EQ(n12, 2u * 10u * 10u);  // 10 x 10 voxel faces, two triangles each
  for (const auto& t : checks.tissues)
    EXPECT_NEAR(t.volume_mm3, voxel_volume(img, t.tissue_id), kExtractedSurfaceVolumeRel * voxel_volume(img, t.tissue_id));
}

TEST(SurfaceExtraction, IsDeterministic) {
  const LabelImage img = three_boxes();
  const SurfaceExtraction a = extract(img, 3), b = extract(img, 3);
  EXPECT_EQ(a.surface.triangles, b.surface.triangles);
  EXPECT_EQ(a.surface.labels, b.surface.labels);
  EXPECT_EQ(a.surface.junctions, b.surface.junctions);
  ASSERT_EQ(a.surface.points.size(), b.surface.points.size());
  for (std::size_t v = 0; v < a.surface.points.size(); ++v) EXPECT_EQ(a.surface.points[v], b.surface.points[v]);
}

TEST(SurfaceExtraction, UnfoldingReportsWhatAFullCheckFinds) {
  // The default phantom (thorax, label 6, outside) at the shipped relaxation folds a few vertices
  // where thin layers bend; the unfolding then re-checks only around the vertices it moves, and
  // the report it returns must be the full check of the final surface, field by field.
  LabelImage ids = make_breast_phantom(PhantomParams{});
  for (auto& l : ids.labels)
    if (l == 6) l = 0;
  const SurfaceExtraction ex = extract(ids, 5, 10, 8);
  EXPECT_GT(ex.unfolded_vertices, 0u);
  const SurfaceCheckReport full = check_surface(ex.surface);
  expect_same_report(ex.checks, full, "default phantom");
  EXPECT_TRUE(full.valid());
}

// A marker clip of 33 voxels (a ball five voxels across) under an island threshold of 128 voxels,
// with one stray clip voxel elsewhere: the stray voxel joins the fat, the clip itself stays (a
// tissue is never removed whole), is reported as kept, and the surface is valid with a closed clip
// of about its voxel volume. Before, the clip vanished and the surface failed its checks.
TEST(SurfaceExtraction, ATissueUnderTheIslandThresholdIsKeptWhole) {
  const LabelImage img = make_image({24, 24, 24}, {0.5, 0.5, 0.5}, [](int i, int j, int k) {
    if (i < 2 || i >= 22 || j < 2 || j >= 22 || k < 2 || k >= 22) return 0;
    if (i == 5 && j == 5 && k == 5) return 2;
    const int di = i - 14, dj = j - 14, dk = k - 14;
    return di * di + dj * dj + dk * dk <= 4 ? 2 : 1;
  });
  const SurfaceExtraction e = extract(img, 2, 10, 128);
  EXPECT_EQ(e.islands.islands, 1u);
  EXPECT_EQ(e.islands.voxels, 1u);
  EXPECT_EQ(e.islands.kept_whole, (std::map<int, std::size_t>{{2, 33}}));
  ASSERT_TRUE(e.checks.valid());
  const TissueSurfaceCheck& clip = e.checks.tissues.at(1);
  EXPECT_GT(clip.triangles, 0u);
  EXPECT_NEAR(clip.volume_mm3, 33 * 0.125, 0.25 * 33 * 0.125);
}

TEST(LabelRepair, RandomLabelsAreMadeWellComposed) {
  // Four regions at random on 14^3 voxels: defects everywhere, and repairs that create new ones in
  // blocks already passed (the repair's later passes revisit only blocks whose voxels changed).
  // The independent full check must find every block sound, with every change a raise.
  std::mt19937 rng(5);
  std::uniform_int_distribution<int> label(0, 3);
  // The relabelled counts, passes and a hash of the result are those of a repair that re-checks
  // every block in every pass (full passes) on the same images: skipping unchanged blocks must make
  // the same fixes in the same order.
  const std::size_t relabelled[3] = {1806, 1829, 1835};
  const int passes[3] = {6, 7, 6};
  const std::uint64_t hashes[3] = {0x95e6bd02e823a647ull, 0xf2b2ee20d0729c39ull, 0x3c0ce558bbf82f72ull};
  for (int trial = 0; trial < 3; ++trial) {
    LabelImage img = make_image({14, 14, 14}, {1, 1, 1}, [&](int, int, int) { return label(rng); });
    ASSERT_FALSE(is_well_composed(img));
    const LabelImage before = img;
    const LabelRepairResult r = make_well_composed(img);
    EXPECT_TRUE(is_well_composed(img)) << "trial " << trial;
    for (std::size_t i = 0; i < img.labels.size(); ++i) EXPECT_GE(img.labels[i], before.labels[i]);
    std::uint64_t hash = 1469598103934665603ull;  // FNV-1a over the labels
    for (int l : img.labels) hash = (hash ^ static_cast<unsigned>(l)) * 1099511628211ull;
    EXPECT_EQ(r.relabelled_voxels, relabelled[trial]) << "trial " << trial;
    EXPECT_EQ(r.passes, passes[trial]) << "trial " << trial;
    EXPECT_EQ(hash, hashes[trial]) << "trial " << trial;
  }
}

TEST(LabelRepair, EdgeAndCornerContactsAreMadeManifold) {
  // Two voxels of tissue 1 touching only along an edge, and two touching only at a corner, next
  // to a tissue-2 voxel pinched between them.
  LabelImage img = make_image({8, 8, 8}, {1, 1, 1}, [](int i, int j, int k) {
    if ((i == 2 && j == 2 && k == 2) || (i == 3 && j == 3 && k == 2)) return 1;  // edge contact
    if ((i == 5 && j == 5 && k == 5) || (i == 6 && j == 6 && k == 6)) return 1;  // corner contact
    if (i == 3 && j == 2 && k == 2) return 2;
    return 0;
  });
  EXPECT_FALSE(is_well_composed(img));
  const LabelImage before = img;
  const LabelRepairResult r = make_well_composed(img);
  EXPECT_TRUE(is_well_composed(img));
  EXPECT_GT(r.relabelled_voxels, 0u);
  // Every change raised a region id (the termination argument of the repair).
  for (std::size_t i = 0; i < img.labels.size(); ++i) EXPECT_GE(img.labels[i], before.labels[i]);
  const SurfaceExtraction ex = extract(before, 2);
  EXPECT_EQ(ex.repair.relabelled_voxels, r.relabelled_voxels);
  EXPECT_TRUE(check_surface(ex.surface).valid());
}

TEST(SurfaceExtraction, RejectsBadIdsAndImagesWithoutBoundary) {
  LabelImage img = three_boxes();
  EXPECT_THROW(extract(img, 2), InputError);  // id 3 with only 2 tissues
  LabelImage empty = make_image({4, 4, 4}, {1, 1, 1}, [](int, int, int) { return 0; });
  EXPECT_THROW(extract(empty, 1), MeshingError);
}

TEST(SurfaceQuality, MatchesHandComputedTriangles) {
  TriSurface s;
  s.tissue_names = {"a"};
  const double h = std::sqrt(3.0) / 2.0;
  s.points = {{0, 0, 0}, {1, 0, 0}, {0.5, h, 0}, {0, 0, 1}, {2, 0, 1}, {0, 1, 1}};
  s.triangles = {{0, 1, 2}, {3, 4, 5}};  // equilateral; right triangle with legs 2 and 1
  s.labels = {{0, 1}, {0, 1}};
  const SurfaceQuality q = surface_quality(s);
  const double small = std::atan(0.5) * 180.0 / EIGEN_PI;  // 26.565 degrees
  EXPECT_NEAR(q.min_angle_deg, small, kAngleDeg);
  EXPECT_NEAR(q.average_min_angle_deg, (60.0 + small) / 2.0, kAngleDeg);
  EXPECT_NEAR(q.p30_percent, 100.0 / 6.0, kRelativeRoundoff);  // 1 of 6 angles below 30 degrees
  // Right triangle: A = 1, p = (1 + 2 + sqrt 5) / 2, h_max = sqrt 5.
  const double q2 = 6.0 / std::sqrt(3.0) * 1.0 / ((3.0 + std::sqrt(5.0)) / 2.0 * std::sqrt(5.0));
  EXPECT_NEAR(q.q_min, q2, kRelativeRoundoff);
  EXPECT_NEAR(q.q_average, (1.0 + q2) / 2.0, kRelativeRoundoff);
}

TEST(SurfaceVtp, RoundTripThroughVtkReader) {
  const TriSurface s = extract(three_boxes(), 3).surface;
  const std::string dir = ::testing::TempDir();
  write_surface_vtp(s, dir + "/surface.vtp");
  write_junctions_vtp(s, dir + "/junctions.vtp");
  vtkNew<vtkXMLPolyDataReader> reader;
  reader->SetFileName((dir + "/surface.vtp").c_str());
  reader->Update();
  vtkPolyData* data = reader->GetOutput();
  ASSERT_EQ(data->GetNumberOfPolys(), static_cast<vtkIdType>(s.triangles.size()));
  ASSERT_EQ(data->GetNumberOfPoints(), static_cast<vtkIdType>(s.points.size()));
  auto* p = vtkIntArray::SafeDownCast(data->GetCellData()->GetArray("label_p"));
  auto* q = vtkIntArray::SafeDownCast(data->GetCellData()->GetArray("label_q"));
  ASSERT_TRUE(p && q);
  vtkNew<vtkIdList> ids;
  for (vtkIdType t = 0; t < data->GetNumberOfPolys(); ++t) {
    data->GetCellPoints(t, ids);
    ASSERT_EQ(ids->GetNumberOfIds(), 3);
    for (int a = 0; a < 3; ++a) EXPECT_EQ(ids->GetId(a), s.triangles[t][a]);
    EXPECT_EQ(p->GetValue(t), s.labels[t][0]);
    EXPECT_EQ(q->GetValue(t), s.labels[t][1]);
  }
  for (vtkIdType v = 0; v < data->GetNumberOfPoints(); ++v)
    EXPECT_EQ(Eigen::Vector3d(data->GetPoint(v)), s.points[v]);  // doubles written in full
  vtkNew<vtkXMLPolyDataReader> lines;
  lines->SetFileName((dir + "/junctions.vtp").c_str());
  lines->Update();
  EXPECT_EQ(lines->GetOutput()->GetNumberOfLines(), static_cast<vtkIdType>(s.junctions.size()));
}
