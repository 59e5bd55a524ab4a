#include "engine/config/ParamFields.hpp"

#include <gtest/gtest.h>

#include <limits>

#include "engine/config/ParamsTestSupport.hpp"

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

// A nested section and its parent, each listing its fields once.
struct Inner : ParamSection<Inner> {
  static constexpr const char* kSection = "inner";
  int window = 5;
  int every = 0;
  template <class Self, class Field>
  static void fields(Self& p, const Field& field) {
    field("window", p.window, OddRange{3, 9});
    field("every", p.every, OffOrRange{2, 10});
  }
};

struct Box : ParamSection<Box> {
  static constexpr const char* kSection = "box";
  int count = 4;
  double ratio = 0.5;
  bool enabled = true;
  std::string label = "front";
  Shade shade = Shade::Dark;
  float width = 1.5f;
  bool dots = false;
  Inner inner;
  template <class Self, class Field>
  static void fields(Self& p, const Field& field) {
    field("count", p.count, Range{1, 10});
    field("ratio", p.ratio, Range{0.0, 1.0});
    field("enabled", p.enabled);
    field("label", p.label);
    field("shade", p.shade, TextForm<Shade>{shadeName, parseShade});
    field("width", p.width, Range{0.5, 2.0});
    field("dots", p.dots, WrittenAsNumber{});
    field(p.inner);
  }
};

std::string yamlOf(const Box& box) {
  cv::FileStorage fs(
      ".yml", cv::FileStorage::WRITE | cv::FileStorage::MEMORY | cv::FileStorage::FORMAT_YAML);
  fs << "box"
     << "{";
  box.write(fs);
  fs << "}";
  return fs.releaseAndGetString();
}

std::string readError(const std::string& yaml) {
  const YamlNode fs = parseYaml(yaml);
  Box box;
  return errorMessage([&] { box.read(fs["box"]); });
}

}  // namespace

TEST(ParamFields, WritesEveryFieldInListOrderWithBooleansAndEnumsAsWordsUnlessSaidOtherwise) {
  EXPECT_EQ(yamlOf(Box{}),
            "%YAML:1.0\n---\nbox:\n   count: 4\n   ratio: 5.0000000000000000e-01\n"
            "   enabled: true\n   label: front\n   shade: dark\n   width: 1.5000000000000000e+00\n"
            "   dots: 0\n   inner:\n      window: 5\n"
            "      every: 0\n");
}

TEST(ParamFields, ReadsWhatItWroteAndKeepsAbsentKeys) {
  Box in;
  in.count = 7;
  in.ratio = 0.125;
  in.enabled = false;
  in.label = "back side";
  in.shade = Shade::Light;
  in.width = 0.75f;
  in.dots = true;
  in.inner.window = 9;
  in.inner.every = 3;
  Box out;
  roundTrip(in, out);
  EXPECT_EQ(out.count, 7);
  EXPECT_EQ(out.ratio, 0.125);
  EXPECT_FALSE(out.enabled);
  EXPECT_EQ(out.label, "back side");
  EXPECT_EQ(out.shade, Shade::Light);
  EXPECT_EQ(out.width, 0.75f);
  EXPECT_TRUE(out.dots);
  EXPECT_EQ(out.inner.window, 9);
  EXPECT_EQ(out.inner.every, 3);

  const YamlNode fs = parseYaml("box: { ratio: 0.25 }\n");
  Box partial;
  partial.read(fs["box"]);
  EXPECT_EQ(partial.ratio, 0.25);
  EXPECT_EQ(partial.count, Box{}.count);
  EXPECT_EQ(partial.inner.window, Inner{}.window);
}

TEST(ParamFields, TheWrittenKeysAreTheKnownOnes) {
  EXPECT_EQ(readError("box: { cuont: 3 }\n"),
            "line 1: box.cuont: unknown key — did you mean box.count?");
  EXPECT_EQ(readError("box:\n  count: 3\n  inner: { windw: 3 }\n"),
            "line 3: box.inner.windw: unknown key — did you mean box.inner.window?");
}

// Read from a file, a value's error names its line and its dotted name in the file.
TEST(ParamFields, ChecksEachRuleNamingLineSectionAndKey) {
  EXPECT_EQ(readError("box: { count: 11 }\n"),
            "line 1: parameter 'box.count' must lie in [1, 10], got 11");
  EXPECT_EQ(readError("box:\n  ratio: 1.5\n"),
            "line 2: parameter 'box.ratio' must lie in [0.000000, 1.000000], got 1.500000");
  EXPECT_EQ(readError("box: { count: many }\n"),
            "line 1: parameter 'box.count' must be an integer");
  EXPECT_EQ(readError("box: { count: '3' }\n"), "line 1: parameter 'box.count' must be an integer");
  EXPECT_EQ(readError("box: { width: 2.5 }\n"),
            "line 1: parameter 'box.width' must lie in [0.500000, 2.000000], got 2.500000");
  EXPECT_EQ(readError("box: { dots: 2 }\n"), "line 1: parameter 'box.dots' must be true or false");
  EXPECT_EQ(readError("box:\n\n  shade: grey\n"),
            "line 3: parameter 'box.shade' must be 'light' or 'dark', got 'grey'");
  EXPECT_EQ(readError("box: { inner: { window: 4 } }\n"),
            "line 1: parameter 'box.inner.window' must be odd");
  EXPECT_EQ(readError("box:\n  inner:\n    window: 11\n"),
            "line 3: parameter 'box.inner.window' must lie in [3, 9], got 11");
  EXPECT_EQ(readError("box: { inner: { every: 1 } }\n"),
            "line 1: parameter 'box.inner.every' must lie in [2, 10], got 1");
  EXPECT_EQ(readError("box: { inner: { every: 0 } }\n"), "(no error)");  // 0: off
  EXPECT_EQ(readError("box: { inner: [1, 2] }\n"),
            "line 1: parameter section 'box.inner' must be a map of key: value");
}

TEST(ParamFields, TheFirstBadFieldInListOrderIsNamed) {
  Box box;
  box.ratio = std::numeric_limits<double>::quiet_NaN();
  box.count = 0;
  EXPECT_EQ(errorMessage([&] { box.check(); }), "parameter 'box.count' must lie in [1, 10], got 0");
  box.count = 1;
  EXPECT_EQ(errorMessage([&] { box.check(); }),
            "parameter 'box.ratio' must be finite (got NaN/inf)");
}

TEST(ParamFields, OneOfAcceptsItsWordsAndNamesThemOtherwise) {
  const OneOf rule{{"cauchy", "huber", "none"}};
  EXPECT_NO_THROW(rule.check("ba.loss", "huber"));
  EXPECT_EQ(errorMessage([&] { rule.check("ba.loss", "Huber"); }),
            "parameter 'ba.loss' must be one of cauchy, huber, none; got 'Huber'");
  EXPECT_EQ(errorMessage([&] { rule.check("ba.loss", ""); }),
            "parameter 'ba.loss' must be one of cauchy, huber, none; got ''");
}
