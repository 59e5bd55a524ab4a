#include "engine/estimation/MotionModelFile.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>

#include "TestPaths.hpp"
#include "engine/core/Error.hpp"

using namespace reftrack;

namespace {

FittedMotionModel sample() {
  Vector6d w1, w2;
  w1 << 1.5, 1.2, 0.9, 1.4, 1.1, 1.3;
  w2 << -0.6, -0.3, 0.05, -0.5, -0.2, -0.4;
  Matrix6d Q = ArMotionModel::diagonalNoise(0.002, 0.003);
  Q(0, 1) = Q(1, 0) = 1e-7;
  FittedMotionModel f;
  f.model = ArMotionModel({w1, w2}, Q);
  f.explainedVariance << 0.9, 0.8, 0.7, 0.85, 0.84, 0.6;
  f.sourceTrajectory = "traj.txt";
  f.frameCount = 321;
  return f;
}

}  // namespace

TEST(MotionModelFile, RoundTripsEveryField) {
  const auto dir = test::freshTempDir("MotionModelFile_RoundTrip");
  const FittedMotionModel f = sample();
  saveMotionModel(dir / "motion.yml", f);
  const FittedMotionModel g = loadMotionModel(dir / "motion.yml");
  ASSERT_EQ(g.model.order(), 2);
  for (int j = 0; j < 2; ++j)
    EXPECT_LT((g.model.weights()[j] - f.model.weights()[j]).norm(), 1e-15);
  EXPECT_LT((g.model.processNoise() - f.model.processNoise()).norm(), 1e-18);
  EXPECT_LT((g.explainedVariance - f.explainedVariance).norm(), 1e-15);
  EXPECT_EQ(g.sourceTrajectory, "traj.txt");
  EXPECT_EQ(g.frameCount, 321);
  EXPECT_FALSE(g.randomWalk);
}

TEST(MotionModelFile, LoadNamesTheBadField) {
  const auto dir = test::freshTempDir("MotionModelFile_Bad");
  saveMotionModel(dir / "good.yml", sample());
  std::ifstream in(dir / "good.yml");
  const std::string good((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  auto messageFor = [&](const std::string& from, const std::string& to) {
    std::string text = good;
    const auto pos = text.find(from);
    EXPECT_NE(pos, std::string::npos) << from;
    text.replace(pos, from.size(), to);
    std::ofstream(dir / "bad.yml") << text;
    try {
      loadMotionModel(dir / "bad.yml");
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(messageFor("order: 2", "order: 3").find("'weights' must be 3x6"), std::string::npos);
  EXPECT_NE(messageFor("order: 2", "order: x").find("'order'"), std::string::npos);
  EXPECT_NE(messageFor("kind: ar", "kind: other").find("'kind'"), std::string::npos);
  EXPECT_NE(messageFor("frame_count: 321", "frame_count: -4").find("'frame_count'"),
            std::string::npos);
  const std::string unknown = messageFor("source_trajectory", "source_x");
  EXPECT_NE(unknown.find("source_x: unknown key — did you mean source_trajectory?"),
            std::string::npos)
      << unknown;
  EXPECT_NE(messageFor("1.5000000000000000e+00", ".Nan").find("NaN"), std::string::npos);
}

TEST(MotionModelFile, MissingOrNonYamlFileIsAnError) {
  const auto dir = test::freshTempDir("MotionModelFile_Missing");
  EXPECT_THROW(loadMotionModel(dir / "none.yml"), Error);
  std::ofstream(dir / "junk.yml") << "{{{{ not yaml";
  EXPECT_THROW(loadMotionModel(dir / "junk.yml"), Error);
}

TEST(MotionModelFile, UnknownKeysNameTheNearestAndTheYamlLineIsOptional) {
  const auto dir = test::freshTempDir("MotionModelFile_Strict");
  saveMotionModel(dir / "good.yml", sample());
  std::ifstream in(dir / "good.yml");
  const std::string good((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const auto load = [&](const std::string& text) {
    std::ofstream(dir / "m.yml") << text;
    try {
      return loadMotionModel(dir / "m.yml").model.order() == 2 ? std::string("loaded")
                                                               : std::string("wrong order");
    } catch (const Error& e) {
      return std::string(e.what());
    }
  };
  const auto replaced = [&](const std::string& from, const std::string& to) {
    std::string text = good;
    const auto pos = text.find(from);
    EXPECT_NE(pos, std::string::npos) << from;
    return pos == std::string::npos ? text : text.replace(pos, from.size(), to);
  };
  // The file's line of `key`, 1-based.
  const auto lineOf = [&](const std::string& key) {
    return std::to_string(1 + std::count(good.begin(), good.begin() + good.find(key), '\n'));
  };
  // A misspelt scalar key and a misspelt matrix (a map in YAML, but a value here).
  EXPECT_NE(load(replaced("frame_count:", "frames_count:"))
                .find("m.yml': line " + lineOf("frame_count:") +
                      ": frames_count: unknown key — did you mean frame_count?"),
            std::string::npos);
  EXPECT_NE(
      load(replaced("weights:", "wieghts:")).find("wieghts: unknown key — did you mean weights?"),
      std::string::npos);
  ASSERT_EQ(good.rfind("%YAML:1.0\n", 0), 0u);
  EXPECT_EQ(load(good.substr(10)), "loaded");
}
