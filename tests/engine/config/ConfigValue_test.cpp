#include "engine/config/ConfigValue.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <limits>

#include "TestPaths.hpp"
#include "engine/config/ParamsTestSupport.hpp"
#include "engine/core/Error.hpp"

using namespace reftrack;

TEST(ConfigValue, ReadsTypedValuesAndKeepsDefaultsForMissingKeys) {
  const YamlNode root = test::parseYaml("s: { d: 2.5, i: 7, b: false, t: hello }\n");
  double d = 1;
  int i = 1;
  bool b = true;
  std::string t = "x";
  double untouched = 42;
  readConfigValue(root["s"], "d", d);
  readConfigValue(root["s"], "i", i);
  readConfigValue(root["s"], "b", b);
  readConfigValue(root["s"], "t", t);
  readConfigValue(root["s"], "missing", untouched);
  EXPECT_EQ(d, 2.5);
  EXPECT_EQ(i, 7);
  EXPECT_FALSE(b);
  EXPECT_EQ(t, "hello");
  EXPECT_EQ(untouched, 42);
  readConfigValue(root["absent_section"], "d", untouched);
  EXPECT_EQ(untouched, 42);
  // An empty section (every key commented out) keeps the defaults too.
  readConfigValue(test::parseYaml("s:\n  # d: 3\n")["s"], "d", untouched);
  EXPECT_EQ(untouched, 42);
}

TEST(ConfigValue, WrongTypesAndNanNameTheLineAndKey) {
  const YamlNode root = test::parseYaml(
      "s:\n  d: abc\n  i: 2.5\n  b: maybe\n  n: .nan\n  inf: .inf\n  q: \"7\"\n  e:\n  t: [a]\n");
  double d = 0;
  int i = 0;
  bool b = false;
  std::string t;
  const YamlNode s = root["s"];
  EXPECT_EQ(test::errorMessage([&] { readConfigValue(s, "d", d); }),
            "line 2: parameter 's.d' must be a number");
  EXPECT_EQ(test::errorMessage([&] { readConfigValue(s, "i", i); }),
            "line 3: parameter 's.i' must be an integer");
  EXPECT_EQ(test::errorMessage([&] { readConfigValue(s, "b", b); }),
            "line 4: parameter 's.b' must be true or false");
  EXPECT_EQ(test::errorMessage([&] { readConfigValue(s, "n", d); }),
            "line 5: parameter 's.n' must be finite (got NaN/inf)");
  EXPECT_EQ(test::errorMessage([&] { readConfigValue(s, "inf", d); }),
            "line 6: parameter 's.inf' must be finite (got NaN/inf)");
  // Quoted, a number is text (YAML 1.2); written without a value, a key is not a number either.
  EXPECT_EQ(test::errorMessage([&] { readConfigValue(s, "q", i); }),
            "line 7: parameter 's.q' must be an integer");
  EXPECT_EQ(test::errorMessage([&] { readConfigValue(s, "e", d); }),
            "line 8: parameter 's.e' must be a number");
  EXPECT_EQ(test::errorMessage([&] { readConfigValue(s, "t", t); }),
            "line 9: parameter 's.t' must be text");
  EXPECT_EQ(test::errorMessage([&] { readConfigValue(root["s"]["d"], "x", d); }),
            "line 2: parameter section 's.d' must be a map of key: value");
}

TEST(ConfigValue, RangeChecksRejectNanAndOutOfRange) {
  EXPECT_NO_THROW(requireFiniteInRange("a.b", 0.5, 0, 1));
  EXPECT_THROW(requireFiniteInRange("a.b", std::numeric_limits<double>::quiet_NaN(), 0, 1), Error);
  EXPECT_THROW(requireFiniteInRange("a.b", std::numeric_limits<double>::infinity(), 0, 1e300),
               Error);
  EXPECT_NE(test::errorMessage([] { requireFiniteInRange("a.b", 2, 0, 1); }).find("'a.b'"),
            std::string::npos);
  EXPECT_NE(test::errorMessage([] { requireIntInRange("c.d", -1, 0, 1); }).find("'c.d'"),
            std::string::npos);
}

TEST(ConfigValue, CheckWithLinesAddsTheLineOfTheNamedParameter) {
  const YamlNode root = test::parseYaml("a:\n  x: 1\n  b:\n    c: 5\n");
  const auto failing = [](const std::string& field) {
    return [field] { requireIntInRange(field, 5, 0, 1); };
  };
  EXPECT_EQ(test::errorMessage([&] { checkWithLines(root, failing("a.b.c")); }),
            "line 4: parameter 'a.b.c' must lie in [0, 1], got 5");
  // Not in the file (a default), through a value, or another message: left as it is.
  EXPECT_EQ(test::errorMessage([&] { checkWithLines(root, failing("a.y")); }),
            "parameter 'a.y' must lie in [0, 1], got 5");
  EXPECT_EQ(test::errorMessage([&] { checkWithLines(root, failing("a.x.z")); }),
            "parameter 'a.x.z' must lie in [0, 1], got 5");
  EXPECT_EQ(test::errorMessage([&] { checkWithLines(root, [] { throw Error("a.x is odd"); }); }),
            "a.x is odd");
  EXPECT_EQ(test::errorMessage([&] { checkWithLines(root, [] {}); }), "(no error)");
}

TEST(ConfigValue, ParameterFilesAndTextsNameThemselvesInEveryError) {
  const auto dir = test::freshTempDir("ConfigValue_ParameterFile");
  writeParameterFile(dir / "p.yml", [](cv::FileStorage& fs) { fs << "answer" << 42; });
  int answer = 0;
  const auto readAnswer = [&](const YamlNode& root) { readConfigValue(root, "answer", answer); };
  readParameterFile(dir / "p.yml", readAnswer);
  EXPECT_EQ(answer, 42);
  readParameterText("{\"answer\": 43}", "parameters (dict)", readAnswer);  // JSON is YAML
  EXPECT_EQ(answer, 43);
  EXPECT_EQ(test::errorMessage(
                [&] { readParameterText("{\"answer\": \"x\"}", "parameters (dict)", readAnswer); }),
            "parameters (dict): line 1: parameter 'answer' must be an integer");
  std::ofstream(dir / "bad.yml") << "answer: [\n";
  EXPECT_EQ(
      test::errorMessage([&] {
        readParameterFile(dir / "bad.yml", readAnswer);
      }).rfind("parameter file '" + (dir / "bad.yml").string() + "' is not valid YAML: line ", 0),
      0u);
  EXPECT_EQ(test::errorMessage([&] { readParameterFile(dir / "absent.yml", readAnswer); }),
            "parameter file '" + (dir / "absent.yml").string() + "' does not exist");
  const auto missing = dir / "no-such-folder" / "p.yml";
  // The atomic writer names the folder before the file could be opened.
  EXPECT_EQ(test::errorMessage([&] { writeParameterFile(missing, [](cv::FileStorage&) {}); }),
            "output folder '" + missing.parent_path().string() + "' does not exist");
  EXPECT_FALSE(std::filesystem::exists(missing));
}
