#include "core/errors.h"
#include "core/tissue_table.h"

#include "support/test_helpers.h"

#include <gtest/gtest.h>

using namespace tissuemesh;

namespace {
TissueTable parse(const std::string& yaml) {
  YamlMap top(YAML::Load(yaml), "", "test.yaml");
  TissueTable t = TissueTable::from_config(top);
  top.finish();
  return t;
}
}  // namespace

TEST(TissueTable, SeveralLabelsMapToOneTissueInListOrder) {
  TissueTable t = parse("tissues: [{name: fat, labels: [1]}, {name: fgt, labels: [2, 7]}]\nignore_labels: [0, 6]");
  ASSERT_EQ(t.tissues().size(), 2u);
  EXPECT_EQ(t.tissue_of_label(1), 1);
  EXPECT_EQ(t.tissue_of_label(2), 2);
  EXPECT_EQ(t.tissue_of_label(7), 2);
  EXPECT_EQ(t.tissue_of_label(6), 0);
  EXPECT_EQ(t.tissue_of_label(9), -1);
  EXPECT_EQ(t.names(), (std::vector<std::string>{"fat", "fgt"}));
}

TEST(TissueTable, DefaultIgnoresLabelZero) {
  TissueTable t = parse("tissues: [{name: a, labels: 3}]");
  EXPECT_EQ(t.tissue_of_label(0), 0);
}

TEST(TissueTable, UnmappedLabelIsNamed) {
  TissueTable t = parse("tissues: [{name: fat, labels: [1]}]");
  const std::string msg = test::input_error_of([&] { t.check_against({{0, 10}, {1, 5}, {4, 3}}, "img.nii"); });
  EXPECT_NE(msg.find("img.nii"), std::string::npos) << msg;
  EXPECT_NE(msg.find("label 4"), std::string::npos) << msg;
}

TEST(TissueTable, EmptyTissueIsNamed) {
  TissueTable t = parse("tissues: [{name: fat, labels: [1]}, {name: tumor, labels: [3]}]");
  const std::string msg = test::input_error_of([&] { t.check_against({{0, 10}, {1, 5}}, "img.nii"); });
  EXPECT_NE(msg.find("tissue 'tumor'"), std::string::npos) << msg;
}

TEST(TissueTable, ToTissueIdsMapsEveryVoxel) {
  TissueTable t = parse("tissues: [{name: fat, labels: [1]}, {name: fgt, labels: [2, 7]}]\nignore_labels: [0, 6]");
  LabelImage img;
  img.dims = {6, 1, 1};
  img.labels = {0, 1, 2, 7, 6, 1};
  EXPECT_EQ(t.to_tissue_ids(img).labels, (std::vector<std::int32_t>{0, 1, 2, 2, 0, 1}));
}

TEST(TissueTable, ConfigErrorsNameTheProblem) {
  EXPECT_NE(test::input_error_of([] { parse("ignore_labels: [0]"); }).find("tissues"), std::string::npos);
  EXPECT_NE(test::input_error_of([] { parse("tissues: [{name: a, labels: [1]}, {name: a, labels: [2]}]"); }).find("listed twice"),
            std::string::npos);
  EXPECT_NE(test::input_error_of([] { parse("tissues: [{name: a, labels: [1]}, {name: b, labels: [1]}]"); })
                .find("label 1 is mapped to more than one"),
            std::string::npos);
  EXPECT_NE(test::input_error_of([] { parse("tissues: [{name: a, labels: [1]}]\nignore_labels: [1]"); }).find("ignore_labels"),
            std::string::npos);
  EXPECT_NE(test::input_error_of([] { parse("tissues: [{name: a, lables: [1]}]"); }).find("lables"), std::string::npos);
  EXPECT_NE(test::input_error_of([] { parse("tissues: [{name: a, labels: [x]}]"); }).find("tissues[0].labels"), std::string::npos);
  EXPECT_NE(test::input_error_of([] { parse("tissues: [{name: a}]"); }).find("has no labels"), std::string::npos);
}

TEST(TissueTable, YamlRoundTrip) {
  TissueTable t = parse("tissues: [{name: fat, labels: [1]}, {name: fgt, labels: [2, 7]}]\nignore_labels: [0, 6]");
  YAML::Emitter out;
  out << YAML::BeginMap;
  t.to_yaml(out);
  out << YAML::EndMap;
  TissueTable back = parse(out.c_str());
  EXPECT_EQ(back.names(), t.names());
  EXPECT_EQ(back.tissues()[1].labels, t.tissues()[1].labels);
  EXPECT_EQ(back.ignored(), t.ignored());
}
