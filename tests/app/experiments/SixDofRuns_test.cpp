#include "app/experiments/SixDofRuns.hpp"

#include <gtest/gtest.h>

#include "app/simulator/SceneSimulator.hpp"
#include "engine/estimation/MotionModelFitter.hpp"
#include "render/context/GlContext.hpp"

namespace reftrack::app {
namespace {

// The 6-DOF tracker end to end on the simulator (marker-prepared map, 640x480, noise SD 2): the
// issue's accuracy targets on a short hand-held stretch, measured against exact ground truth.
// Mean <= 0.5 px and p95 <= 1.5 px are the product targets; 60 frames keep the test ~30 s.
TEST(SixDofRuns, HandheldMeetsTheCubeErrorTargets) {
  const auto gl = render::createHeadlessContext();
  SimulationOptions o;
  o.preset = "handheld";
  o.frames = 60;
  const SimulatedSequence s = simulateSequence(o);
  EXPECT_GE(s.preparation.map.matches.size(), 300u);
  const TrackerRun run = runPoseTracker(s, TrackerParams{}, "regularised");
  EXPECT_EQ(run.lostFrames, 0) << (run.lostReasons.empty() ? "" : run.lostReasons.front());
  ASSERT_TRUE(run.evaluation.cubeErrorPx.has_value());
  EXPECT_LT(run.evaluation.cubeErrorPx->mean, 0.5);
  EXPECT_LT(run.evaluation.cubeErrorPx->p95, 1.5);
}

// Static camera, Q fitted (paper Sec. 5.3) to another static path: the regulariser's
// frame-to-frame jitter must be at least 3x below standard least squares (the target),
// and below 0.05 px.
TEST(SixDofRuns, RegulariserCutsStaticJitterThreefold) {
  const auto gl = render::createHeadlessContext();
  SimulationOptions o;
  o.preset = "static";
  o.frames = 40;
  const SimulatedSequence s = simulateSequence(o);
  TumTrajectory recorded;
  for (int k = 0; k < o.frames; ++k)
    recorded.poses.push_back({k / o.fps, s.groundTruth.poses[0].worldToCamera});
  const ArMotionModel motion =
      MotionModelFitter::fit(MotionModelFitter::motionVectors(recorded), 0).model;
  TrackerParams params;
  params.pose.estimator = PoseEstimatorKind::Standard;
  const TrackerRun standard = runPoseTracker(s, params, "standard", motion);
  params.pose.estimator = PoseEstimatorKind::Regularised;
  const TrackerRun regularised = runPoseTracker(s, params, "regularised", motion);
  ASSERT_TRUE(standard.evaluation.jitterPx && regularised.evaluation.jitterPx);
  EXPECT_LT(*regularised.evaluation.jitterPx, 0.05);
  EXPECT_LT(3.0 * *regularised.evaluation.jitterPx, *standard.evaluation.jitterPx);
}

}  // namespace
}  // namespace reftrack::app
