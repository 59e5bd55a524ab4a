#include "app/research/sixdof/SixDofRuns.hpp"

#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "app/simulator/CameraEffects.hpp"
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

// Rolling shutter alone (the webcam level: a 20 ms readout at 30 fps, so rows are exposed up to
// 10 ms before or after the middle row the pose stands for). Told the readout
// (pose.rolling_shutter_readout = 0.6, its estimate off), the tracker moves each corner back along
// its frame-to-frame motion and must cut the cube error of the global-shutter model on the same
// frames by at least a quarter. Measured on exactly this run (`experiment-6dof --size 320x240
// --frames 40 --effects rolling-shutter --no-fit-q [--known-readout]`, regularised): mean 0.274 ->
// 0.162 px (and one frame lost -> none); at 640x480, 60 frames: 0.332 -> 0.120 px. Not told
// (pose.estimate_rolling_shutter on), the tracker estimates the readout from the
// tracked frames (RollingShutterEstimator) and must cut it by a quarter too, though its first ten
// moving frames are corrected with 0: measured on the same run 0.172 px, none lost.
TEST(SixDofRuns, RollingShutterReadoutKnownOrEstimatedCutsTheCubeError) {
  const auto gl = render::createHeadlessContext();
  SimulationOptions o;
  o.preset = "handheld";
  o.frames = 40;
  o.size = {320, 240};
  o.effects = cameraEffectsFor("rolling-shutter", o.size);
  ASSERT_GT(o.effects.readoutMs, 0.0);
  const SimulatedSequence s = simulateSequence(o);
  TrackerParams params;
  params.pose.estimateRollingShutter = false;
  const TrackerRun global = runPoseTracker(s, params, "global shutter");
  params.pose.rollingShutterReadout = o.effects.readoutMs * o.fps / 1000.0;
  const TrackerRun corrected = runPoseTracker(s, params, "readout known");
  TrackerParams estimating;
  estimating.pose.estimateRollingShutter = true;  // off by default (real clips: README)
  const TrackerRun estimated = runPoseTracker(s, estimating, "readout estimated");
  ASSERT_TRUE(global.evaluation.cubeErrorPx && corrected.evaluation.cubeErrorPx &&
              estimated.evaluation.cubeErrorPx);
  EXPECT_EQ(corrected.lostFrames, 0)
      << (corrected.lostReasons.empty() ? "" : corrected.lostReasons.front());
  EXPECT_EQ(estimated.lostFrames, 0)
      << (estimated.lostReasons.empty() ? "" : estimated.lostReasons.front());
  EXPECT_LT(corrected.evaluation.cubeErrorPx->mean, 0.75 * global.evaluation.cubeErrorPx->mean);
  EXPECT_LT(estimated.evaluation.cubeErrorPx->mean, 0.75 * global.evaluation.cubeErrorPx->mean);
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

// The walkaround with six references (issue 13's targets: >= 99% tracked, mean <= 0.3 px, p95 <=
// 1.0 px over 1000 frames). The first 150 frames of the 1000-frame path at its own pace: from A
// out to 1.65 m and across the front to +45 deg, past references 0, 1 and 3, so the tracker
// hands over between pairs.
// Bounds: every frame tracked (a loss would show as < 100%), cube error mean <= 0.4 px and p95 <=
// 1.2 px (the full-run targets plus a third for the small sample's larger spread).
TEST(SixDofRuns, WalkaroundWithSixReferencesMeetsTheCubeErrorTargets) {
  const auto gl = render::createHeadlessContext();
  SimulationOptions o;
  o.preset = "walkaround";
  o.frames = 1000;
  o.references = 6;
  SceneSimulator sim(o);
  SimulatedSequence s;
  s.options = o;
  s.camera = sim.camera();
  s.references = prepareSimulatedReferences(sim, 6);
  s.preparation.map = s.references->pair(0, 1);
  for (int k = 0; k < 150; ++k) {
    cv::Mat grey;
    cv::cvtColor(sim.renderFrame(k), grey, cv::COLOR_BGR2GRAY);
    s.frames.push_back(grey);
    s.groundTruth.poses.push_back({k / o.fps, sim.framePose(k)});
  }
  const TrackerRun multi = runMultiReferenceTracker(s, TrackerParams{}, "6 references");
  for (const auto& [pair, frames] : multi.pairUse)
    std::cout << "pair " << pair << ": " << frames << "\n";
  ASSERT_TRUE(multi.evaluation.cubeErrorPx.has_value());
  std::cout << "6 references: " << multi.estimate.poses.size() << "/150 tracked, cube mean "
            << multi.evaluation.cubeErrorPx->mean << " px, p95 "
            << multi.evaluation.cubeErrorPx->p95 << " px\n";
  EXPECT_EQ(multi.lostFrames, 0) << (multi.lostReasons.empty() ? "" : multi.lostReasons.front());
  EXPECT_LE(multi.evaluation.cubeErrorPx->mean, 0.4);
  EXPECT_LE(multi.evaluation.cubeErrorPx->p95, 1.2);
  EXPECT_GE(multi.pairUse.size(), 2u);  // it handed over at least once
}

}  // namespace
}  // namespace reftrack::app
