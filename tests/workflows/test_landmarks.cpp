// Landmarks (workflows/landmarks.h): a point on a node maps to that node exactly, a point inside a
// tet to the barycentric combination of its corners, a point outside is refused by name; the CSV
// reader refuses malformed files naming the line.
#include "workflows/landmarks.h"

#include "core/errors.h"
#include "support/model_fixture.h"
#include "support/test_paths.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

namespace tissuemesh {
namespace {

std::vector<Eigen::Vector3d> sheared(const Model& m) {
  std::vector<Eigen::Vector3d> out = m.nodes;
  for (Eigen::Vector3d& p : out) p += Eigen::Vector3d(0.2 * p.z(), -0.1 * p.x(), 0.03 * p.y() * p.y());
  return out;
}

TEST(Landmarks, OnANodeMapsToThatNodeExactly) {
  const Model m = test::block_model();
  const int node = 37;
  const auto where = locate_landmarks(m, {{"on_node", m.nodes[node]}});
  ASSERT_EQ(where.size(), 1u);
  const std::vector<Eigen::Vector3d> other = sheared(m);
  EXPECT_EQ(landmark_position(where[0], other), other[node]);
  EXPECT_EQ(landmark_position(where[0], m.nodes), m.nodes[node]);
}

TEST(Landmarks, InsideATetIsItsBarycentricCombination) {
  const Model m = test::block_model();
  const auto& el = m.elements[123];
  const double w[4] = {0.1, 0.2, 0.3, 0.4};
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
  for (int c = 0; c < 4; ++c) p += w[c] * m.nodes[el[c]];
  const auto where = locate_landmarks(m, {{"inside", p}});
  ASSERT_EQ(where[0].element, 123);
  EXPECT_EQ(where[0].tissue, m.tissue_ids[123]);
  const std::vector<Eigen::Vector3d> other = sheared(m);
  Eigen::Vector3d expected = Eigen::Vector3d::Zero();
  for (int c = 0; c < 4; ++c) expected += w[c] * other[el[c]];
  EXPECT_LE((landmark_position(where[0], other) - expected).norm(), 1e-12);
  EXPECT_LE((landmark_position(where[0], m.nodes) - p).norm(), 1e-12);
}

TEST(Landmarks, OutsideIsRefusedByName) {
  const Model m = test::block_model();  // the box [0, 20] x [0, 10] x [0, 10] mm
  try {
    locate_landmarks(m, {{"inside", {5, 5, 5}}, {"nipple", {10, -0.5, 5}}});
    FAIL() << "a point outside the mesh was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("'nipple'"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("outside the mesh"), std::string::npos) << e.what();
  }
}

std::string write_csv(const std::filesystem::path& dir, const std::string& name, const std::string& text) {
  const std::filesystem::path p = dir / name;
  std::ofstream(p) << text;
  return p.string();
}

TEST(LandmarkCsv, ReadsNamesAndCoordinatesWithAHeader) {
  const auto points = read_landmarks_csv(write_csv(test::scratch_dir(), "ok.csv", "name,x,y,z\n# a comment\n\ntumour_tip, 1.5, -2, 3e1\nnipple,0,0,0\n"));
  ASSERT_EQ(points.size(), 2u);
  EXPECT_EQ(points[0].name, "tumour_tip");
  EXPECT_EQ(points[0].position_mm, Eigen::Vector3d(1.5, -2.0, 30.0));
}

TEST(LandmarkCsv, MalformedFilesNameTheLine) {
  const std::pair<const char*, const char*> cases[] = {
      {"fields.csv", "a,1,2\n"},          {"number.csv", "a,1,2,3\nb,1,x,3\n"},
      {"twice.csv", "a,1,2,3\na,4,5,6\n"}, {"nan.csv", "a,1,nan,3\n"},
      {"empty.csv", "name,x,y,z\n"}};
  const std::filesystem::path dir = test::scratch_dir();
  for (const auto& [name, text] : cases) {
    const std::string path = write_csv(dir, name, text);
    EXPECT_THROW(read_landmarks_csv(path), InputError) << name;
  }
  try {
    read_landmarks_csv(write_csv(dir, "line.csv", "a,1,2,3\nb,1,x,3\n"));
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("line.csv:2"), std::string::npos) << e.what();
  }
  EXPECT_THROW(read_landmarks_csv("/nonexistent/points.csv"), InputError);
}

}  // namespace
}  // namespace tissuemesh
