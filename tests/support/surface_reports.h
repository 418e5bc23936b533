// Field-by-field comparison of two surface check reports (surface/surface_checks.h), shared by the
// tests of the re-check after moved points and of the extraction's unfolding, which must report
// exactly what a full check of the same surface finds.
#pragma once

#include "surface/surface_checks.h"

#include <gtest/gtest.h>

#include <string>

namespace tissuemesh::test {

/// Every field of two reports equal (volumes bit for bit: the same sums in the same order);
/// `context` names the case in failure messages.
inline void expect_same_report(const SurfaceCheckReport& a, const SurfaceCheckReport& b, const std::string& context) {
  ASSERT_EQ(a.tissues.size(), b.tissues.size()) << context;
  for (std::size_t i = 0; i < a.tissues.size(); ++i) {
    const TissueSurfaceCheck &x = a.tissues[i], &y = b.tissues[i];
    EXPECT_EQ(x.tissue_id, y.tissue_id) << context;
    EXPECT_EQ(x.triangles, y.triangles) << context;
    EXPECT_EQ(x.vertices, y.vertices) << context;
    EXPECT_EQ(x.open_edges, y.open_edges) << context;
    EXPECT_EQ(x.nonmanifold_edges, y.nonmanifold_edges) << context;
    EXPECT_EQ(x.misoriented_edges, y.misoriented_edges) << context;
    EXPECT_EQ(x.nonmanifold_vertices, y.nonmanifold_vertices) << context;
    EXPECT_EQ(x.intersecting_pairs, y.intersecting_pairs) << context << ", tissue " << x.name;
    EXPECT_EQ(x.volume_mm3, y.volume_mm3) << context << ", tissue " << x.name;
  }
  EXPECT_EQ(a.duplicate_triangles, b.duplicate_triangles) << context;
  EXPECT_EQ(a.junction_edges, b.junction_edges) << context;
  EXPECT_EQ(a.junction_edges_off_junction, b.junction_edges_off_junction) << context;
  EXPECT_EQ(a.valid(), b.valid()) << context;
}

}  // namespace tissuemesh::test
