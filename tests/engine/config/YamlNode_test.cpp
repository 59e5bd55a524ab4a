// YamlNode: names, lines and YAML 1.2's core-schema reads of one node.
#include "engine/config/YamlNode.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "engine/config/ParamsTestSupport.hpp"

using namespace reftrack;
using namespace reftrack::test;

TEST(YamlNode, NamesAndLinesFollowTheFile) {
  const YamlNode root = parseYaml("a:\n  b: 1\nviews:\n  - {T: 2}\n  -\n    T: 3\n");
  EXPECT_EQ(root.name(), "");
  EXPECT_EQ(root["a"]["b"].name(), "a.b");
  EXPECT_EQ(root["a"]["b"].line(), 2);
  EXPECT_EQ(root["a"]["b"].key(), "b");
  EXPECT_EQ(root["views"].item(1)["T"].name(), "views[1].T");
  EXPECT_EQ(root["views"].item(1)["T"].line(), 6);
  EXPECT_EQ(root["views"].size(), 2u);
  // Absent keys keep a name (for messages) and the line of the map that lacks them.
  const YamlNode absent = root["a"]["c"]["d"];
  EXPECT_FALSE(absent.present());
  EXPECT_EQ(absent.name(), "a.c.d");
  EXPECT_EQ(absent.line(), 1);
  EXPECT_EQ(errorMessage([&] { root["a"]["b"]["c"]; }), "line 2: a.b must be a map of key: value");
  EXPECT_NE(errorMessage([&] { root["views"].item(2); }).find("outside views"), std::string::npos);
  std::vector<std::string> keys;
  for (const YamlNode& child : root.children()) keys.push_back(child.key());
  EXPECT_EQ(keys, (std::vector<std::string>{"a", "views"}));
}

TEST(YamlNode, NumbersFollowTheCoreSchemaAndOpenCvsSpellings) {
  const YamlNode n = parseYaml(
      "list: [1, -2.5, +3, .5, 1., 1e3, 2.5E-2, .inf, -.Inf, .NaN, .Nan, 1e999, \"4\", 0x10, abc, "
      "1.2.3, '', ~]\n")["list"];
  const std::vector<double> expected = {1, -2.5, 3, 0.5, 1, 1000, 0.025, INFINITY, -INFINITY};
  for (std::size_t i = 0; i < expected.size(); ++i) EXPECT_EQ(n.item(i).number(), expected[i]) << i;
  EXPECT_TRUE(std::isnan(*n.item(9).number()));
  EXPECT_TRUE(std::isnan(*n.item(10).number()));
  EXPECT_EQ(n.item(11).number(), INFINITY);  // beyond a double: rounds to infinity
  for (std::size_t i = 12; i < n.size(); ++i) EXPECT_FALSE(n.item(i).number()) << i;
}

TEST(YamlNode, IntegersBooleansAndText) {
  const YamlNode r = parseYaml(
      "i: [7, -7, +7, 2147483647, 2147483648, 7.0, '7', seven]\n"
      "b: [true, True, TRUE, 1, false, False, FALSE, 0, yes, on, 'true', 2]\n"
      "t: [plain, 'single', \"double\", 5, ~, [x]]\n");
  const YamlNode i = r["i"], b = r["b"], t = r["t"];
  EXPECT_EQ(i.item(0).integer(), 7);
  EXPECT_EQ(i.item(1).integer(), -7);
  EXPECT_EQ(i.item(2).integer(), 7);
  EXPECT_EQ(i.item(3).integer(), 2147483647);
  for (std::size_t k = 4; k < i.size(); ++k) EXPECT_FALSE(i.item(k).integer()) << k;
  for (std::size_t k = 0; k < 4; ++k) EXPECT_EQ(b.item(k).boolean(), true) << k;
  for (std::size_t k = 4; k < 8; ++k) EXPECT_EQ(b.item(k).boolean(), false) << k;
  for (std::size_t k = 8; k < b.size(); ++k) EXPECT_FALSE(b.item(k).boolean()) << k;  // YAML 1.1's
  EXPECT_EQ(t.item(0).text(), "plain");
  EXPECT_EQ(t.item(1).text(), "single");
  EXPECT_EQ(t.item(2).text(), "double");
  EXPECT_EQ(t.item(3).text(), "5");
  EXPECT_FALSE(t.item(4).text());
  EXPECT_FALSE(t.item(5).text());
  EXPECT_EQ(errorMessage([&] { t.item(5).fail("no good"); }), "line 3: no good");
}

TEST(YamlNode, AnAliasReadsAsItsAnchor) {
  const YamlNode r = parseYaml("w: &w 9\nsection: &s {a: 1}\nx: *w\ncopy: *s\n");
  EXPECT_EQ(r["x"].integer(), 9);
  EXPECT_EQ(r["x"].line(), 3);
  EXPECT_EQ(r["copy"]["a"].integer(), 1);
  EXPECT_EQ(r["copy"]["a"].name(), "copy.a");
}
