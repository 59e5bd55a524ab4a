#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>

#include "app/commands/CommandTestSupport.hpp"
#include "engine/geometry/PinholeCamera.hpp"
#include "engine/geometry/TumTrajectory.hpp"

using namespace reftrack;

namespace {

// Ground truth: a camera sliding along x above the marker, looking straight down; 100 frames.
TumTrajectory slide() {
  TumTrajectory t;
  const Eigen::Matrix3d down = Eigen::Vector3d(1, -1, -1).asDiagonal();  // z_cam = -z_world
  for (int k = 0; k < 100; ++k) {
    const Eigen::Vector3d C(-0.1 + 0.002 * k, 0.02, 0.5);
    t.poses.push_back({k / 30.0, RigidPose(down, -down * C)});
  }
  return t;
}

}  // namespace

TEST(EvalCommand, KnownOffsetGivesKnownAteInJsonAndWritesPlots) {
  const auto dir = test::freshTempDir("EvalCommand_Offset");
  const TumTrajectory gt = slide();
  TumTrajectory est;
  for (std::size_t k = 0; k < gt.poses.size(); ++k) {
    if (k >= 80) break;  // the tracker lost the last 20 frames
    est.poses.push_back({gt.poses[k].timestamp,
                         gt.poses[k].worldToCamera *
                             RigidPose(Eigen::Matrix3d::Identity(), Eigen::Vector3d(0, 0, -0.01))});
  }
  gt.save(dir / "gt.txt");
  est.save(dir / "est.txt");
  Eigen::Matrix3d K;
  K << 500, 0, 319.5, 0, 500, 239.5, 0, 0, 1;
  PinholeCamera(K, {640, 480}).save(dir / "camera.yml");

  const auto r = test::runReftrack("eval --gt " + (dir / "gt.txt").string() + " --est " +
                                       (dir / "est.txt").string() + " --camera " +
                                       (dir / "camera.yml").string() + " --json",
                                   dir);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  // One JSON object on stdout.
  ASSERT_FALSE(r.out.empty());
  EXPECT_EQ(r.out.front(), '{');
  EXPECT_EQ(r.out[r.out.find_last_not_of('\n')], '}');
  // Camera centres moved 10 mm along world z for every frame: ATE exactly 10 mm.
  EXPECT_NE(r.out.find("\"ate_translation_mm\": {\"count\": 80, \"rmse\": 10, \"mean\": 10"),
            std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("\"tracked_fraction\": 0.8"), std::string::npos) << r.out;
  // A 10 mm depth change at 0.5 m: cube vertices move by about 2% of their offset from the
  // principal point, a couple of pixels; the exact value is checked in TrajectoryEvaluator_test.
  EXPECT_NE(r.out.find("\"cube_error_px\": {\"count\": 640"), std::string::npos) << r.out;
  const cv::Mat errorPlot = cv::imread((dir / "est.error.png").string());
  const cv::Mat topPlot = cv::imread((dir / "est.topview.png").string());
  EXPECT_EQ(errorPlot.size(), cv::Size(900, 600));
  EXPECT_EQ(topPlot.size(), cv::Size(900, 600));

  const auto text = test::runReftrack(
      "eval --no-plots --gt " + (dir / "gt.txt").string() + " --est " + (dir / "est.txt").string(),
      dir);
  ASSERT_EQ(text.exitCode, 0) << text.err;
  EXPECT_NE(text.out.find("tracked 80.0%"), std::string::npos) << text.out;
  EXPECT_NE(text.out.find("needs --camera"), std::string::npos) << text.out;
}

TEST(EvalCommand, ErrorsAreClear) {
  const auto dir = test::freshTempDir("EvalCommand_Errors");
  EXPECT_EQ(test::runReftrack("eval --gt nothing.txt --est nothing.txt", dir).exitCode, 2);
  slide().save(dir / "gt.txt");
  std::ofstream(dir / "bad.txt") << "0 1 2\n";
  const auto r = test::runReftrack(
      "eval --gt " + (dir / "gt.txt").string() + " --est " + (dir / "bad.txt").string(), dir);
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_NE(r.err.find("line 1"), std::string::npos) << r.err;
}
