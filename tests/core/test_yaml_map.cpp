#include "core/errors.h"
#include "core/yaml_map.h"
#include "support/test_paths.h"

#include "support/test_helpers.h"

#include <gtest/gtest.h>

#include <fstream>

using namespace tissuemesh;

TEST(YamlMap, TypedValuesAndDefaults) {
  YamlMap m(YAML::Load("a: 2.5\nb: 3\nc: true\nd: hello\ne: [1, 2]"), "", "f.yaml");
  EXPECT_DOUBLE_EQ(m.number("a", 0), 2.5);
  EXPECT_EQ(m.integer("b", 0), 3);
  EXPECT_TRUE(m.boolean("c", false));
  EXPECT_EQ(m.text("d", ""), "hello");
  EXPECT_EQ(m.integers("e", {}), (std::vector<int>{1, 2}));
  EXPECT_DOUBLE_EQ(m.number("missing", 7.0), 7.0);
  EXPECT_NO_THROW(m.finish());
}

TEST(YamlMap, UnknownKeyIsAnErrorWithItsPath) {
  YamlMap top(YAML::Load("direct: {facet_sise_mm: 2}"), "", "f.yaml");
  YamlMap direct = top.map("direct");
  direct.number("facet_size_mm", 1.0);
  const std::string msg = test::input_error_of([&] { direct.finish(); });
  EXPECT_NE(msg.find("f.yaml: direct.facet_sise_mm: unknown key"), std::string::npos) << msg;
  EXPECT_NE(msg.find("facet_size_mm"), std::string::npos) << msg;  // lists the known keys
}

TEST(YamlMap, WrongTypesAndRangesNameKeyAndValue) {
  YamlMap m(YAML::Load("a: big\nb: -1\nc: 7\nd: maybe\ne: {x: 1}"), "sec", "f.yaml");
  EXPECT_NE(test::input_error_of([&] { m.number("a", 0); }).find("f.yaml: sec.a: expected a number, got 'big'"), std::string::npos);
  EXPECT_NE(test::input_error_of([&] { m.positive("b", 1); }).find("sec.b: must be positive, got -1"), std::string::npos);
  EXPECT_NE(test::input_error_of([&] { m.in_range("c", 1, 0, 5); }).find("sec.c: must lie in [0, 5], got 7"), std::string::npos);
  EXPECT_NE(test::input_error_of([&] { m.boolean("d", false); }).find("expected true or false"), std::string::npos);
  EXPECT_NE(test::input_error_of([&] { m.number("e", 0); }).find("sec.e: expected a number"), std::string::npos);
}

TEST(YamlMap, FileErrorsNameTheFileAndLine) {
  const auto dir = test::scratch_dir();
  EXPECT_NE(test::input_error_of([&] { load_yaml_file((dir / "none.yaml").string()); }).find("none.yaml: cannot open"),
            std::string::npos);
  std::ofstream(dir / "bad.yaml") << "a: 1\nb: [1, 2\n";
  const std::string msg = test::input_error_of([&] { load_yaml_file((dir / "bad.yaml").string()); });
  EXPECT_NE(msg.find("bad.yaml: invalid YAML at line"), std::string::npos) << msg;
  std::ofstream(dir / "list.yaml") << "- 1\n- 2\n";
  EXPECT_NE(test::input_error_of([&] { load_yaml_file((dir / "list.yaml").string()); }).find("must be a mapping"),
            std::string::npos);
}
