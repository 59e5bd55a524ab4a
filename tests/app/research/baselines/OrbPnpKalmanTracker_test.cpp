#include "app/research/baselines/OrbPnpKalmanTracker.hpp"

#include <gtest/gtest.h>

#include "app/research/sixdof/SixDofRuns.hpp"
#include "render/context/GlContext.hpp"

namespace reftrack::app {
namespace {

// The baseline must be a working tracker, or the benchmark ratios mean nothing: on a short
// hand-held stretch it tracks every frame once initialised, within a few pixels (ORB keypoints
// are located to about a pixel; the Kalman filter lags the hand shake).
TEST(OrbPnpKalmanTracker, TracksASimulatedSequence) {
  const auto gl = render::createHeadlessContext();
  SimulationOptions o;
  o.preset = "handheld";
  o.frames = 30;
  const SimulatedSequence s = simulateSequence(o);
  const TrackerRun run = runOrbBaseline(s);
  EXPECT_EQ(run.lostFrames, 0);
  ASSERT_TRUE(run.evaluation.cubeErrorPx.has_value());
  EXPECT_LT(run.evaluation.cubeErrorPx->mean, 5.0);
}

}  // namespace
}  // namespace reftrack::app
