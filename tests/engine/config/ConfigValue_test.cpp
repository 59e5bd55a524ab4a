#include "engine/config/ConfigValue.hpp"

#include <gtest/gtest.h>

#include <limits>

#include "TestPaths.hpp"
#include "engine/config/ParamsTestSupport.hpp"
#include "engine/core/Error.hpp"

using namespace reftrack;

TEST(ConfigValue, ReadsTypedValuesAndKeepsDefaultsForMissingKeys) {
  auto fs = test::parseYaml("s: { d: 2.5, i: 7, b: false, t: hello }\n");
  double d = 1;
  int i = 1;
  bool b = true;
  std::string t = "x";
  double untouched = 42;
  readConfigValue(fs["s"], "s", "d", d);
  readConfigValue(fs["s"], "s", "i", i);
  readConfigValue(fs["s"], "s", "b", b);
  readConfigValue(fs["s"], "s", "t", t);
  readConfigValue(fs["s"], "s", "missing", untouched);
  EXPECT_EQ(d, 2.5);
  EXPECT_EQ(i, 7);
  EXPECT_FALSE(b);
  EXPECT_EQ(t, "hello");
  EXPECT_EQ(untouched, 42);
  readConfigValue(fs["absent_section"], "absent_section", "d", untouched);
  EXPECT_EQ(untouched, 42);
}

TEST(ConfigValue, WrongTypesAndNanNameTheKey) {
  auto fs = test::parseYaml("s: { d: abc, i: 2.5, b: maybe, n: .nan, inf: .inf }\n");
  double d = 0;
  int i = 0;
  bool b = false;
  EXPECT_NE(test::errorMessage([&] { readConfigValue(fs["s"], "s", "d", d); }).find("'s.d'"),
            std::string::npos);
  EXPECT_NE(test::errorMessage([&] { readConfigValue(fs["s"], "s", "i", i); }).find("'s.i'"),
            std::string::npos);
  EXPECT_NE(test::errorMessage([&] { readConfigValue(fs["s"], "s", "b", b); }).find("'s.b'"),
            std::string::npos);
  EXPECT_NE(test::errorMessage([&] { readConfigValue(fs["s"], "s", "n", d); }).find("NaN"),
            std::string::npos);
  EXPECT_NE(test::errorMessage([&] { readConfigValue(fs["s"], "s", "inf", d); }).find("'s.inf'"),
            std::string::npos);
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

TEST(ConfigValue, WriteParameterFileIsReadBackAndRefusesAMissingFolder) {
  const auto dir = test::freshTempDir("ConfigValue_WriteParameterFile");
  writeParameterFile(dir / "p.yml", [](cv::FileStorage& fs) { fs << "answer" << 42; });
  int answer = 0;
  readParameterFile(dir / "p.yml",
                    [&](const cv::FileNode& root) { readConfigValue(root, "", "answer", answer); });
  EXPECT_EQ(answer, 42);
  const auto missing = dir / "no-such-folder" / "p.yml";
  // The atomic writer names the folder before the file could be opened.
  EXPECT_EQ(test::errorMessage([&] { writeParameterFile(missing, [](cv::FileStorage&) {}); }),
            "output folder '" + missing.parent_path().string() + "' does not exist");
  EXPECT_FALSE(std::filesystem::exists(missing));
}
