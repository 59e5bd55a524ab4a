// End-to-end checks of `reftrack show-map` through the built binary (headless PNG, bad maps).
#include <gtest/gtest.h>

#include <fstream>
#include <opencv2/imgcodecs.hpp>

#include "CommandTestSupport.hpp"
#include "TestPaths.hpp"
#include "app/mapview/TwoViewTestMap.hpp"
#include "engine/reference/ReferenceMap.hpp"

using namespace reftrack;
namespace fs = std::filesystem;

namespace {

using test::CommandRun;

// `reftrack show-map ARGS`, run through the built binary.
CommandRun showMap(const std::string& args, const fs::path& scratch) {
  return test::runReftrack("show-map " + args, scratch);
}

// A saved 320x240 map (textured images, 60 points).
fs::path savedMap(const fs::path& dir) {
  test::twoViewTestMap(60, 4, true).save(dir / "map");
  return dir / "map";
}

}  // namespace

TEST(ShowMapCommand, HeadlessScreenshotIsWrittenAndNotBlank) {
  const fs::path dir = test::freshTempDir("ShowMapCommand_png");
  const fs::path map = savedMap(dir);
  const CommandRun run = showMap(
      "--map " + map.string() + " --headless --screenshot " + (dir / "map.png").string(), dir);
  ASSERT_EQ(run.exitCode, 0) << run.err;
  const cv::Mat png = cv::imread((dir / "map.png").string(), cv::IMREAD_COLOR);
  ASSERT_EQ(png.size(), cv::Size(640, 480));
  // Top: the (random-texture) reference images; bottom: dark background with points/frusta.
  cv::Scalar mean, sd;
  cv::meanStdDev(png(cv::Rect(0, 0, 640, 240)), mean, sd);
  EXPECT_GT(sd[0], 30.0);
  cv::meanStdDev(png(cv::Rect(0, 300, 640, 180)), mean, sd);
  EXPECT_GT(sd[0] + sd[1] + sd[2], 10.0);  // not a uniform background
}

TEST(ShowMapCommand, TruncatedMapFileIsReportedAsSuch) {
  const fs::path dir = test::freshTempDir("ShowMapCommand_truncated");
  const fs::path map = savedMap(dir);
  const fs::path file = map / ReferenceMap::kFileName;
  const std::string text = test::readTextFile(file);
  std::ofstream(file, std::ios::trunc) << text.substr(0, text.size() / 2);
  const CommandRun run = showMap(
      "--map " + map.string() + " --headless --screenshot " + (dir / "map.png").string(), dir);
  EXPECT_EQ(run.exitCode, 1);
  EXPECT_NE(run.err.find("map.yml"), std::string::npos) << run.err;
  EXPECT_TRUE(run.err.find("truncated") != std::string::npos ||
              run.err.find("corrupt") != std::string::npos)
      << run.err;
  EXPECT_FALSE(fs::exists(dir / "map.png"));
}

TEST(ShowMapCommand, UsageErrors) {
  const fs::path dir = test::freshTempDir("ShowMapCommand_usage");
  EXPECT_EQ(showMap("--map " + (dir / "missing").string() + " --headless --screenshot x.png", dir)
                .exitCode,
            2);
  const fs::path map = savedMap(dir);
  const CommandRun noShot = showMap("--map " + map.string() + " --headless", dir);
  EXPECT_EQ(noShot.exitCode, 2);
  EXPECT_NE(noShot.err.find("--screenshot"), std::string::npos) << noShot.err;
}
