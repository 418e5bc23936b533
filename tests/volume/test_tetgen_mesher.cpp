// TetGen backend (docs/verification.md, "Cross-check with TetGen"): the surface complexes of the
// surface-pipeline tests meshed with TetGen: conforming, every tissue's volume equal to the volume
// its surface encloses (TetGen only adds points on the input facets, never moves them), the
// interfaces of the surface and no others, the quality bound, determinism, and parameter errors.
#include "core/errors.h"
#include "quality/conformity.h"
#include "surface/surface_checks.h"
#include "surface/surface_projection.h"
#include "surface/surface_remesh.h"
#include "volume/tetgen_mesher.h"
#include "support/complex_meshes.h"
#include "support/tolerances.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <set>

using namespace tissuemesh;
using namespace tissuemesh::test;

namespace {

TetgenResult mesh(const TriSurface& s, const TetgenParams& params = {}) {
  Progress progress;
  return tetgen_mesh(s, params, progress);
}

/// Longest circumradius / shortest edge over the tets (the measure TetGen's -q bounds).
double max_radius_edge(const TetMesh& m) {
  double worst = 0.0;
  for (const auto& t : m.tets) {
    const Eigen::Vector3d a = m.points[t[0]], b = m.points[t[1]] - a, c = m.points[t[2]] - a, d = m.points[t[3]] - a;
    const Eigen::Vector3d centre =
        (b.squaredNorm() * c.cross(d) + c.squaredNorm() * d.cross(b) + d.squaredNorm() * b.cross(c)) /
        (2.0 * b.dot(c.cross(d)));
    const double shortest = std::min({b.norm(), c.norm(), d.norm(), (c - b).norm(), (d - b).norm(), (d - c).norm()});
    worst = std::max(worst, centre.norm() / shortest);
  }
  return worst;
}

/// Per-tissue tet volume must equal the volume the surface encloses.
void expect_surface_volumes(const TetMesh& m, const TriSurface& s) {
  const SurfaceCheckReport checks = check_surface(s);
  const std::vector<double> volume = tissue_volumes(m);
  for (const TissueSurfaceCheck& c : checks.tissues)
    EXPECT_NEAR(volume[c.tissue_id], c.volume_mm3, kRelativeRoundoff * c.volume_mm3) << c.name;
}

}  // namespace

TEST(TetgenMesher, NestedSpheresConformingWithTheSurfaceVolumes) {
  const TriSurface s = remeshed(nested_spheres(), 2, 300).surface;
  const TetgenResult r = mesh(s);
  ASSERT_NO_THROW(r.mesh.validate("TetGen spheres"));
  const ConformityReport c = check_conformity(r.mesh);
  EXPECT_TRUE(c.conforming());
  EXPECT_EQ(c.inverted_tets, 0u);
  EXPECT_EQ(c.duplicate_node_groups, 0u);
  EXPECT_EQ(interfaces(c), (std::set<std::pair<int, int>>{{0, 1}, {1, 2}}));  // the inner ball never touches outside
  expect_surface_volumes(r.mesh, s);
  EXPECT_GT(r.mesh.tets.size(), r.mesh.points.size());  // a real volume mesh, not just a few tets
  EXPECT_EQ(r.switches, "pzQAaYq2/0");
  EXPECT_LE(max_radius_edge(r.mesh), 2.0 * (1.0 + kRelativeRoundoff));
}

TEST(TetgenMesher, ThreeBoxesKeepTheirTripleJunctionInterfaces) {
  const TriSurface s = remeshed(three_boxes(), 3, 400).surface;
  const TetgenResult r = mesh(s);
  const ConformityReport c = check_conformity(r.mesh);
  EXPECT_TRUE(c.conforming());
  EXPECT_EQ(interfaces(c), (std::set<std::pair<int, int>>{{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}}));
  expect_surface_volumes(r.mesh, s);
  EXPECT_LE(max_radius_edge(r.mesh), 2.0 * (1.0 + kRelativeRoundoff));
}

TEST(TetgenMesher, VolumeBoundRefinesAndRunsAreIdentical) {
  const TriSurface s = remeshed(nested_spheres(), 2, 300).surface;
  const TetgenResult coarse = mesh(s);
  TetgenParams fine;
  fine.max_volume_mm3 = {{"t1", 0.5}, {"t2", 0.5}};
  const TetgenResult a = mesh(s, fine), b = mesh(s, fine);
  EXPECT_GT(a.mesh.tets.size(), 2 * coarse.mesh.tets.size());
  // The bound holds inside the tissues; tets at the kept surface may stay larger (header comment),
  // so the median, not the maximum, is below it.
  std::vector<double> volumes;
  for (const auto& k : a.mesh.tets)
    volumes.push_back(signed_tet_volume(a.mesh.points[k[0]], a.mesh.points[k[1]], a.mesh.points[k[2]], a.mesh.points[k[3]]));
  std::nth_element(volumes.begin(), volumes.begin() + volumes.size() / 2, volumes.end());
  EXPECT_LE(volumes[volumes.size() / 2], 0.5);
  EXPECT_EQ(a.mesh.points, b.mesh.points);
  EXPECT_EQ(a.mesh.tets, b.mesh.tets);
  EXPECT_EQ(a.mesh.tissue_ids, b.mesh.tissue_ids);
}

TEST(TetgenMesher, PointSizesGradeTheMesh) {
  // Largest circumradius 0.5 mm on one half of the spheres' surface points and 2 mm on the other:
  // TetGen splits a tet while its circumradius exceeds the value at one of its vertices, and
  // interpolates the values at the points it adds, so the inside follows the halves.
  const TriSurface s = remeshed(nested_spheres(), 2, 300).surface;
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  for (const auto& p : s.points) centre += p / static_cast<double>(s.points.size());
  std::vector<double> sizes;
  for (const auto& p : s.points) sizes.push_back(p.x() < centre.x() ? 0.5 : 2.0);
  Progress progress;
  const TetgenResult r = tetgen_mesh(s, TetgenParams{}, progress, sizes);
  EXPECT_EQ(r.switches, "pzQAamYq2/0");
  EXPECT_TRUE(check_conformity(r.mesh).conforming());
  expect_surface_volumes(r.mesh, s);
  // Median circumradius of the tets well inside each half (3 mm from the dividing plane).
  std::vector<double> fine, coarse;
  for (const auto& k : r.mesh.tets) {
    const Eigen::Vector3d a = r.mesh.points[k[0]], b = r.mesh.points[k[1]] - a, c = r.mesh.points[k[2]] - a,
                          d = r.mesh.points[k[3]] - a;
    const Eigen::Vector3d centre_offset =
        (b.squaredNorm() * c.cross(d) + c.squaredNorm() * d.cross(b) + d.squaredNorm() * b.cross(c)) /
        (2.0 * b.dot(c.cross(d)));
    const double x = a.x() + (b.x() + c.x() + d.x()) / 4.0 - centre.x();
    if (x < -3.0) fine.push_back(centre_offset.norm());
    if (x > 3.0) coarse.push_back(centre_offset.norm());
  }
  ASSERT_FALSE(fine.empty());
  ASSERT_FALSE(coarse.empty());
  auto median = [](std::vector<double> v) {
    std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
    return v[v.size() / 2];
  };
  EXPECT_LE(median(fine), 0.5);
  EXPECT_LT(median(fine), 0.5 * median(coarse));
  sizes.pop_back();
  EXPECT_THROW(tetgen_mesh(s, TetgenParams{}, progress, sizes), InputError);
  sizes.push_back(-1.0);
  EXPECT_THROW(tetgen_mesh(s, TetgenParams{}, progress, sizes), InputError);
}

TEST(TetgenMesher, BadParametersNameTheKey) {
  const TriSurface s = remeshed(nested_spheres(), 2, 300).surface;
  auto message = [&](const TetgenParams& p) {
    try {
      mesh(s, p);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  TetgenParams p;
  p.radius_edge_ratio = 1.0;
  EXPECT_NE(message(p).find("tetgen.radius_edge_ratio"), std::string::npos);
  p = {};
  p.min_dihedral_deg = 75;
  EXPECT_NE(message(p).find("tetgen.min_dihedral_deg"), std::string::npos);
  p = {};
  p.max_volume_mm3 = {{"bone", 1.0}};
  EXPECT_NE(message(p).find("unknown tissue 'bone'"), std::string::npos);
  p.max_volume_mm3 = {{"t1", 0.0}};
  EXPECT_NE(message(p).find("tetgen.max_volume_mm3.t1"), std::string::npos);
}
