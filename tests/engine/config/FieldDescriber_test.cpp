#include "engine/config/FieldDescriber.hpp"

#include <gtest/gtest.h>

#include <set>

#include "engine/config/ParamsTestSupport.hpp"
#include "engine/config/TrackerParams.hpp"

using namespace reftrack;
using namespace reftrack::test;

namespace {

enum class Shade { Light, Dark };
std::string shadeName(Shade s) { return s == Shade::Light ? "light" : "dark"; }
Shade parseShade(const std::string& text) {
  if (text == "light") return Shade::Light;
  if (text == "dark") return Shade::Dark;
  throw Error("parameter 'box.shade' must be 'light' or 'dark', got '" + text + "'");
}

struct Spacing {  // a rule of another kind, with its own describe()
  void check(const std::string&, const int&) const {}
  std::string describe() const { return "a multiple of 4"; }
};

struct Inner : ParamSection<Inner> {
  static constexpr const char* kSection = "inner";
  int window = 5;
  template <class Self, class Field>
  static void fields(Self& p, const Field& field) {
    field("window", p.window, OddRange{3, 9}).help("window side");
  }
};

struct Box : ParamSection<Box> {
  static constexpr const char* kSection = "box";
  int count = 4;
  double ratio = 0.5;
  bool enabled = true;
  std::string label = "front";
  Shade shade = Shade::Dark;
  bool dots = false;
  int every = 0;
  int spacing = 8;
  Inner inner;
  template <class Self, class Field>
  static void fields(Self& p, const Field& field) {
    field("count", p.count, Range{1, 10}).help("how many");
    field("ratio", p.ratio, Range{0.0, 1e-3});
    field("enabled", p.enabled).help("on or off");
    field("label", p.label);
    field("shade", p.shade, TextForm<Shade>{shadeName, parseShade});
    field("dots", p.dots, WrittenAsNumber{});
    field("every", p.every, OffOrRange{2, 10});
    field("spacing", p.spacing, Spacing{});
    field(p.inner);
  }
};

// The dotted keys of every value in a map, nested maps walked, in file order.
void collectKeys(const YamlNode& map, const std::string& prefix, std::vector<std::string>& out) {
  for (const YamlNode& child : map.children()) {
    const std::string key = prefix.empty() ? child.key() : prefix + "." + child.key();
    if (child.isMap())
      collectKeys(child, key, out);
    else
      out.push_back(key);
  }
}

}  // namespace

TEST(FieldDescriber, DescribesEveryFieldInListOrderWithItsValueRuleAndMeaning) {
  const std::vector<ParamDescription> d = describeParams(Box{});
  ASSERT_EQ(d.size(), 9u);
  const auto row = [](const ParamDescription& p) {
    return p.key + " | " + p.value + " | " + p.allowed + " | " + p.help;
  };
  EXPECT_EQ(row(d[0]), "box.count | 4 | [1, 10] | how many");
  EXPECT_EQ(row(d[1]), "box.ratio | 0.5 | [0.0, 0.001] | ");
  EXPECT_EQ(row(d[2]), "box.enabled | true | true | false | on or off");
  EXPECT_EQ(row(d[3]), "box.label | \"front\" | text | ");
  EXPECT_EQ(row(d[4]), "box.shade | \"dark\" | light | dark | ");
  EXPECT_EQ(row(d[5]), "box.dots | 0 | 1 | 0 | ");
  EXPECT_EQ(row(d[6]), "box.every | 0 | 0 (off) or [2, 10] | ");
  EXPECT_EQ(row(d[7]), "box.spacing | 8 | a multiple of 4 | ");
  EXPECT_EQ(row(d[8]), "box.inner.window | 5 | odd in [3, 9] | window side");
  EXPECT_EQ(d[8].section(), "box.inner");
  EXPECT_EQ(d[8].name(), "window");
}

TEST(FieldDescriber, TheValuesAreThoseOfTheGivenStruct) {
  Box box;
  box.count = 7;
  box.label = "say \"hi\"";
  box.inner.window = 9;
  const std::vector<ParamDescription> d = describeParams(box);
  EXPECT_EQ(d[0].value, "7");
  EXPECT_EQ(d[3].value, "\"say \\\"hi\\\"\"");
  EXPECT_EQ(d[8].value, "9");
}

TEST(FieldDescriber, WritesNumbersInTheirShortestExactForm) {
  EXPECT_EQ(yamlValueText(8.0), "8.0");
  EXPECT_EQ(yamlValueText(-1.0), "-1.0");
  EXPECT_EQ(yamlValueText(0.01), "0.01");
  EXPECT_EQ(yamlValueText(1e-4), "1e-4");
  EXPECT_EQ(yamlValueText(1e5), "1e5");
  EXPECT_EQ(yamlValueText(2.5e-12), "2.5e-12");
  EXPECT_EQ(yamlValueText(0.1 + 0.2), "0.30000000000000004");
  EXPECT_EQ(yamlValueText(1.5f), "1.5");
  EXPECT_EQ(yamlValueText(2147483647), "2147483647");
  EXPECT_EQ(yamlValueText(false), "false");
  EXPECT_EQ(yamlValueText(std::string()), "\"\"");
  EXPECT_EQ(yamlValueText(std::string("a\\b")), "\"a\\\\b\"");
  // Each reads back to the same value, as the parameter readers read it.
  for (const double v : {8.0, 0.01, 1e-4, 1e5, 2.5e-12, 0.1 + 0.2, -3.75, 1e300}) {
    const YamlNode root = parseYaml("v: " + yamlValueText(v) + "\n");
    ASSERT_TRUE(root["v"].number().has_value()) << v;
    EXPECT_EQ(*root["v"].number(), v);
  }
}

TEST(FieldDescriber, EveryKeyTrackerParamsSavesIsDescribedInOrderWithAMeaning) {
  cv::FileStorage fs(
      ".yml", cv::FileStorage::WRITE | cv::FileStorage::MEMORY | cv::FileStorage::FORMAT_YAML);
  TrackerParams{}.write(fs);
  std::vector<std::string> saved;
  collectKeys(parseYaml(fs.releaseAndGetString()), "", saved);

  const std::vector<ParamDescription> described = describeParams(TrackerParams{});
  std::vector<std::string> keys;
  for (const ParamDescription& d : described) {
    keys.push_back(d.key);
    EXPECT_FALSE(d.help.empty()) << d.key << " has no meaning";
    EXPECT_EQ(d.help.find('\n'), std::string::npos) << d.key << ": more than one line";
    EXPECT_LE(d.help.size(), 110u) << d.key << ": not a one-line meaning";
    EXPECT_FALSE(d.allowed.empty()) << d.key;
    EXPECT_FALSE(d.value.empty()) << d.key;
  }
  EXPECT_EQ(keys, saved);
  EXPECT_EQ(std::set<std::string>(keys.begin(), keys.end()).size(), keys.size());
  EXPECT_GT(keys.size(), 100u);
}
