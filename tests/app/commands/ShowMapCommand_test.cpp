// End-to-end checks of `reftrack show-map` through the built binary (headless PNG, bad maps).
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdlib>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <random>
#include <sstream>

#include "CommandTestSupport.hpp"
#include "TestPaths.hpp"
#include "engine/reference/ReferenceMap.hpp"

using namespace reftrack;
namespace fs = std::filesystem;

namespace {

using test::CommandRun;

// `reftrack show-map ARGS`, run through the built binary.
CommandRun showMap(const std::string& args, const fs::path& scratch) {
  return test::runReftrack("show-map " + args, scratch);
}

// A saved 320x240 map: textured images, 60 points 1-2 m in front of A, B 0.2 m to its right.
fs::path savedMap(const fs::path& dir) {
  Eigen::Matrix3d K;
  K << 300, 0, 159.5, 0, 300, 119.5, 0, 0, 1;
  ReferenceMap map;
  map.camera = PinholeCamera(K, cv::Size(320, 240));
  map.T_B = RigidPose(Eigen::Matrix3d::Identity(), Eigen::Vector3d(-0.2, 0.0, 0.0));
  map.imageA = cv::Mat(240, 320, CV_8UC3);
  cv::randu(map.imageA, 0, 255);
  map.imageB = map.imageA.clone();
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> u(-0.3, 0.3), z(1.0, 2.0);
  for (int i = 0; i < 60; ++i) {
    const Eigen::Vector3d P(u(rng), u(rng), z(rng));
    const Eigen::Vector2d a = map.camera.project(P), b = map.camera.project(map.T_B * P);
    map.cornersA.push_back({cv::Point2f(static_cast<float>(a.x()), static_cast<float>(a.y())), 20});
    map.cornersB.push_back({cv::Point2f(static_cast<float>(b.x()), static_cast<float>(b.y())), 20});
    map.matches.push_back({i, i, P});
  }
  map.poseSource = "test";
  map.save(dir / "map");
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
  std::string text;
  {
    std::ifstream in(file);
    std::stringstream s;
    s << in.rdbuf();
    text = s.str();
  }
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
