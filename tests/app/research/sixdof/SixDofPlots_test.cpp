#include "app/research/sixdof/SixDofPlots.hpp"

#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>

#include "TestPaths.hpp"

namespace reftrack::app {
namespace {

// Both plots are written as readable PNGs from runs with poses and motion vectors; the motion
// plot stacks the six component panels.
TEST(SixDofPlots, WritesTheCubeErrorAndMotionComponentPlots) {
  SimulatedSequence s;
  s.options.fps = 30;
  s.camera = PinholeCamera::fromFieldOfView({640, 480}, 60);
  TrackerRun a, b;
  a.name = "standard";
  b.name = "regularised";
  for (int k = 0; k < 20; ++k) {
    FrameEvaluation f;
    f.timestamp = k / 30.0;
    f.cubeErrorPx = 0.1 + 0.01 * k;
    a.evaluation.frames.push_back(f);
    b.evaluation.frames.push_back(f);
    Vector6d x = Vector6d::Constant(0.001 * k);
    a.motion.push_back(x);
    b.motion.push_back(k % 5 == 0 ? std::optional<Vector6d>() : std::optional<Vector6d>(x));
  }
  const auto dir = test::freshTempDir("SixDofPlots");
  writeCubeErrorPlot(s, {&a, &b}, dir / "cube.png");
  writeMotionComponentsPlot(s, a, b, dir / "motion.png");
  const cv::Mat cube = cv::imread((dir / "cube.png").string());
  const cv::Mat motion = cv::imread((dir / "motion.png").string());
  ASSERT_FALSE(cube.empty());
  ASSERT_FALSE(motion.empty());
  EXPECT_EQ(motion.rows, 6 * 260);
}

}  // namespace
}  // namespace reftrack::app
