// The remesher's size field (docs/surface-pipeline.md, "Approach grading"): the approach grading
// (its config keys and the size it asks for around the tumor and the corridor) and the graded cap
// around stuck edges.
#include "core/errors.h"
#include "surface/approach_field.h"
#include "surface/graded_size_cap.h"
#include "pipeline/mesh_config.h"
#include "surface/surface_projection.h"
#include "surface/surface_remesh.h"
#include "support/surface_images.h"
#include "support/tolerances.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

using namespace tissuemesh;
using namespace tissuemesh::test;

TEST(ApproachField, SizeIsRatioSmallerAtTheFocusAndGrowsBackSmoothly) {
  const LabelImage img = nested_spheres();
  const TriSurface input = extract(img, 2).surface;
  ApproachParams p;
  p.enabled = true;
  p.target_tissue = "t2";  // the inner ball
  p.entry_tissue = "t1";   // entered through the outer ball's surface
  p.corridor_radius_mm = 1.0;
  p.ratio = 3.0;
  p.falloff_mm = 2.0;
  const ApproachField field(input, p);
  // auto entry: the outer surface vertex nearest the centroid, about 9 mm from it.
  double nearest = INFINITY;
  for (std::size_t t = 0; t < input.triangles.size(); ++t)
    if (input.labels[t] == std::array<int, 2>{0, 1})
      for (int v : input.triangles[t]) nearest = std::min(nearest, (input.points[v] - field.target_centroid()).norm());
  EXPECT_DOUBLE_EQ((field.entry() - field.target_centroid()).norm(), nearest);
  EXPECT_DOUBLE_EQ(field.relative_size(field.target_centroid()), 1.0 / 3.0);
  EXPECT_DOUBLE_EQ(field.relative_size(field.entry()), 1.0 / 3.0);  // the corridor's end
  const Eigen::Vector3d away = field.target_centroid() - 3.0 * (field.entry() - field.target_centroid());
  EXPECT_DOUBLE_EQ(field.relative_size(away), 1.0);
  // Monotone in between (smoothstep), strictly inside the falloff.
  const Eigen::Vector3d dir = (away - field.target_centroid()).normalized();
  double last = 0.0;
  for (double r = field.target_radius_mm(); r <= field.target_radius_mm() + 2.0; r += 0.25) {
    const double s = field.relative_size(field.target_centroid() + r * dir);
    EXPECT_GE(s, last);
    last = s;
  }
  // Graded remeshing: edges in the focus are shorter than beyond the falloff.
  RemeshOptions options;
  options.target_vertices = 400;
  options.max_deviation_mm = 0.5 * img.spacing.norm();
  options.relative_size = [&field](const Eigen::Vector3d& x) { return field.relative_size(x); };
  const SurfaceProjection on_input(input);
  Progress progress;
  const RemeshResult r = remesh_surface(input, on_input, options, progress);
  EXPECT_EQ(r.surface.points.size(), 400u);
  EXPECT_TRUE(r.checks.valid());
  const ApproachGrading g = measure_grading(r.surface, field);
  ASSERT_GT(g.inside_edges, 0u);
  ASSERT_GT(g.outside_edges, 0u);
  // The grading criterion itself: mean edge inside the focus / beyond the falloff <= 1 / ratio.
  EXPECT_LE(g.ratio(), 1.0 / p.ratio);
}

TEST(ApproachParams, ConfigErrorsNameTheKey) {
  const std::string tissues = "tissues:\n  - {name: a, labels: [1]}\n";
  const auto parse = [&](const std::string& extra) { return MeshConfig::parse(YAML::Load(tissues + extra), "t.yaml"); };
  EXPECT_NO_THROW(parse("pipeline: surface\nsurface: {target_vertices: 100}\napproach: {enabled: true, entry: [1, 2, 3]}\n"));
  const auto message = [&](const std::string& extra) {
    try {
      parse(extra);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message("approach: {enabled: true}\n").find("approach"), std::string::npos);  // direct pipeline
  EXPECT_NE(message("pipeline: surface\nsurface: {target_vertices: 100}\napproach: {entry: [1, 2]}\n").find("approach.entry"),
            std::string::npos);
  EXPECT_NE(message("pipeline: surface\nsurface: {target_vertices: 100}\napproach: {ratio: 0.5}\n").find("approach.ratio"),
            std::string::npos);
  EXPECT_NE(message("pipeline: surface\nsurface: {target_edge_mm: -1}\n").find("surface.target_edge_mm"), std::string::npos);
}

TEST(GradedSizeCap, IsTheFactorTimesTheEdgeAtItsMidpointAndGrowsByTheGradation) {
  GradedSizeCap cap(2.0, 0.5, Eigen::AlignedBox3d(Eigen::Vector3d::Constant(-5.0), Eigen::Vector3d::Constant(20.0)));
  const Eigen::Vector3d m(1.0, 2.0, 3.0), far(30.0, 2.0, 3.0);
  EXPECT_TRUE(std::isinf(cap(m)));  // no edge yet
  cap.add(m, 0.7, 10.0);
  EXPECT_NEAR(cap(m), 1.4, kRelativeRoundoff);
  EXPECT_NEAR(cap(m + Eigen::Vector3d(0.0, 4.0, 0.0)), 1.4 + 0.5 * 4.0, kRelativeRoundoff);
  EXPECT_TRUE(std::isinf(cap(far)));  // beyond (10 - 1.4) / 0.5 mm the cap could not matter
  cap.add(far, 0.5, 10.0);            // the minimum over edges
  EXPECT_NEAR(cap(far + Eigen::Vector3d(0.0, 0.0, 2.0)), 1.0 + 0.5 * 2.0, kRelativeRoundoff);
  EXPECT_NEAR(cap(m), 1.4, kRelativeRoundoff);
  cap.add(m, 6.0, 10.0);  // factor * length above `largest`: not entered
  EXPECT_EQ(cap.size(), 2u);
}
