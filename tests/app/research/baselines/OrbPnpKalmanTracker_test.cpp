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

// reset() is a cold start: after it, a frame gets exactly the pose a fresh tracker gives it (its
// own PnP pose), not one filtered from the frames before.
TEST(OrbPnpKalmanTracker, ResetForgetsTheFilteredState) {
  const auto gl = render::createHeadlessContext();
  SimulationOptions o;
  o.preset = "handheld";
  o.frames = 30;
  const SimulatedSequence s = simulateSequence(o);
  OrbPnpKalmanTracker continued(s.preparation.map), tracked(s.preparation.map),
      fresh(s.preparation.map);
  for (int k = 0; k < 20; ++k) {
    continued.process(s.frames[static_cast<std::size_t>(k)]);
    tracked.process(s.frames[static_cast<std::size_t>(k)]);
  }
  const std::optional<RigidPose> withState = continued.process(s.frames[29]);
  tracked.reset();
  const std::optional<RigidPose> afterReset = tracked.process(s.frames[29]);
  const std::optional<RigidPose> cold = fresh.process(s.frames[29]);
  ASSERT_TRUE(withState && afterReset && cold);
  EXPECT_LT(RigidPose::translationDistance(*afterReset, *cold), 1e-9);
  EXPECT_LT(RigidPose::rotationDistance(*afterReset, *cold), 1e-9);
  // Without the reset the filter's prediction from frame 19 pulls the pose away from it.
  EXPECT_GT(RigidPose::translationDistance(*withState, *cold), 1e-6);
}

}  // namespace
}  // namespace reftrack::app
