// The surface pipeline's TetGen volume stage (volume.mesher: tetgen, volume/surface_tetgen.h) on
// small remeshed complexes: conforming, every tissue's volume the volume its surface encloses (the
// surface is kept, and the repairs after TetGen leave it where it is), the surface's interfaces and
// no others; a tet budget lands within 10 %, and one below what the kept surface needs is an
// input error naming the key and a budget that can be met; the config keys are checked.
#include "core/errors.h"
#include "core/yaml_map.h"
#include "quality/conformity.h"
#include "surface/surface_checks.h"
#include "surface/surface_quality.h"
#include "volume/surface_tetgen.h"
#include "support/complex_meshes.h"
#include "support/tolerances.h"

#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <set>
#include <tuple>

using namespace tissuemesh;
using namespace tissuemesh::test;

namespace {

SurfaceTetgenResult mesh(const TriSurface& s, const VolumeMeshParams& params = {}) {
  const double edge = surface_quality(s).mean_edge_mm;
  Progress progress;
  return mesh_surface_with_tetgen(
      s, [edge](const Eigen::Vector3d&) { return edge; }, params, TetgenParams{}, progress);
}

std::set<std::pair<int, int>> surface_interfaces(const TriSurface& s) {
  std::set<std::pair<int, int>> out;
  for (const auto& l : s.labels) out.insert({std::min(l[0], l[1]), std::max(l[0], l[1])});
  return out;
}

void expect_surface_kept(const SurfaceTetgenResult& r, const TriSurface& s) {
  const ConformityReport c = check_conformity(r.mesh);
  EXPECT_TRUE(c.conforming());
  EXPECT_EQ(interfaces(c), surface_interfaces(s));
  const SurfaceCheckReport checks = check_surface(s);
  const std::vector<double> volume = tissue_volumes(r.mesh);
  for (const TissueSurfaceCheck& t : checks.tissues)
    EXPECT_NEAR(volume[t.tissue_id], t.volume_mm3, kRelativeRoundoff * t.volume_mm3) << t.name;
}

VolumeMeshParams read(const std::string& text) {
  YamlMap m(YAML::Load(text), "volume", "test");
  return VolumeMeshParams::from_yaml(m);
}

std::string error_of(const std::string& text) {
  try {
    read(text);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(SurfaceTetgen, KeepsTheSurfaceVolumesAndInterfaces) {
  for (const auto& [image, tissues, budget] :
       {std::tuple{nested_spheres(), 2, 300}, std::tuple{three_boxes(), 3, 400}}) {
    const TriSurface s = remeshed(image, tissues, budget).surface;
    const SurfaceTetgenResult r = mesh(s);
    expect_surface_kept(r, s);
    EXPECT_GT(r.mesh.tets.size(), r.mesh.points.size());
    EXPECT_TRUE(r.budget.empty());
    EXPECT_DOUBLE_EQ(r.cell_edge_factor, 1.5);
  }
}

TEST(SurfaceTetgen, TargetTetsLandsWithinTenPercent) {
  const TriSurface s = remeshed(nested_spheres(), 2, 300).surface;
  const std::size_t coarse = mesh(s).mesh.tets.size();
  VolumeMeshParams p;
  p.mesher = "tetgen";
  p.target_tets = 4 * coarse;
  const SurfaceTetgenResult r = mesh(s, p);
  ASSERT_FALSE(r.budget.empty());
  EXPECT_LE(r.budget.size(), 5u);  // the mesh without a size bound, then at most four rounds
  EXPECT_NEAR(static_cast<double>(r.budget.back().count) / static_cast<double>(p.target_tets), 1.0, 0.10);
  // The repairs after TetGen add at most a few nodes: the mesh kept is within the budget too.
  EXPECT_NEAR(static_cast<double>(r.mesh.tets.size()) / static_cast<double>(p.target_tets), 1.0, 0.10);
  EXPECT_LT(r.cell_edge_factor, 1.5);
  expect_surface_kept(r, s);
}

TEST(SurfaceTetgen, NoSizeBoundGivesTheFewestTets) {
  const TriSurface s = remeshed(nested_spheres(), 2, 300).surface;
  VolumeMeshParams p;
  p.cell_edge_factor = 0.0;
  const SurfaceTetgenResult r = mesh(s, p);
  expect_surface_kept(r, s);
  EXPECT_LT(r.mesh.tets.size(), mesh(s).mesh.tets.size());
  EXPECT_EQ(r.cell_edge_factor, 0.0);
}

TEST(SurfaceTetgen, ABudgetUnderTheSurfacesOwnNeedNamesTheKey) {
  const TriSurface s = remeshed(nested_spheres(), 2, 300).surface;
  VolumeMeshParams p;
  p.mesher = "tetgen";
  p.target_tets = 20;
  try {
    mesh(s, p);
    FAIL() << "20 tets cannot hold a surface of 300 vertices";
  } catch (const InputError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("volume.target_tets"), std::string::npos) << m;
    EXPECT_NE(m.find("raise volume.target_tets to at least"), std::string::npos) << m;
  }
}

TEST(SurfaceTetgen, ConfigKeys) {
  EXPECT_EQ(read("{}").mesher, "cgal");
  const VolumeMeshParams t = read("{mesher: tetgen, target_tets: 45000}");
  EXPECT_EQ(t.mesher, "tetgen");
  EXPECT_EQ(t.target_tets, 45000u);
  EXPECT_NE(error_of("{mesher: gmsh}").find("volume.mesher"), std::string::npos);
  EXPECT_EQ(read("{target_tets: 1000}").target_tets, 1000u);  // CGAL meets it with a size factor
  EXPECT_NE(error_of("{mesher: tetgen, cell_growth: 1}").find("volume.cell_growth"), std::string::npos);
  EXPECT_NE(error_of("{mesher: tetgen, target_tets: -1}").find("volume.target_tets"), std::string::npos);
  EXPECT_EQ(read("{mesher: tetgen, cell_edge_factor: 0}").cell_edge_factor, 0.0);
  EXPECT_NE(error_of("{cell_edge_factor: 0}").find("volume.cell_edge_factor"), std::string::npos);
}
