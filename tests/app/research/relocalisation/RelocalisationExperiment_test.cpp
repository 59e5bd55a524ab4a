#include "app/research/relocalisation/RelocalisationExperiment.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <memory>
#include <thread>

#include "app/research/sixdof/SimulatedSequence.hpp"
#include "engine/core/Error.hpp"
#include "engine/evaluation/TrajectoryEvaluator.hpp"
#include "render/context/GlContext.hpp"

using namespace reftrack;
using namespace reftrack::app;

namespace {

SimulationOptions walkaroundOneFrame() {
  SimulationOptions o;
  o.preset = "walkaround";
  o.frames = 1;
  o.references = 6;
  return o;
}

// The walkaround's six references and their prepared map, drawn from by the experiments below
// (declaration order is construction order: the GL context first).
// Issue 13's experiment with its ORB relocaliser (the product's default keypoints are SIFT since
// issue 24, chosen on real footage and tested there: MultiReferenceTrackerRealFootage_test; SIFT
// made this test 3x slower for the same rates).
TrackerParams orbRelocalisation() {
  TrackerParams p;
  p.relocalisation.keypoints = "orb";
  return p;
}

struct WalkaroundSixReferences {
  std::unique_ptr<render::GlContext> gl = render::createHeadlessContext();
  SceneSimulator sim{walkaroundOneFrame()};
  TrackerParams params = orbRelocalisation();
  MultiReferenceMap map = prepareSimulatedReferences(sim, 6, {}, params.relocalisation);
};

}  // namespace

TEST(RelocalisationExperiment, PoseCubeErrorIsTheMeanVertexDisplacement) {
  const PinholeCamera camera = PinholeCamera::fromFieldOfView({640, 480}, 60.0);
  const RigidPose truth(
      Eigen::AngleAxisd(0.3, Eigen::Vector3d(1, 0.2, 0).normalized()).toRotationMatrix(),
      Eigen::Vector3d(0.05, -0.1, 0.9));
  EXPECT_NEAR(poseCubeErrorPx(camera, truth, truth), 0.0, 1e-12);
  // 2 mm sideways in the camera frame: every vertex moves by fx * 0.002 / z.
  const RigidPose moved(truth.rotation(), truth.translation() + Eigen::Vector3d(0.002, 0, 0));
  double expected = 0.0;
  for (const Eigen::Vector3d& X : cubeVertices(0.1))
    expected += camera.fx() * 0.002 / (truth * X).z();
  expected /= 8.0;
  EXPECT_NEAR(poseCubeErrorPx(camera, truth, moved), expected, 1e-9);
  // A pose that puts the cube behind the camera is as wrong as it gets.
  const RigidPose behind(truth.rotation(), -truth.translation() - Eigen::Vector3d(0, 0, 2));
  EXPECT_GT(poseCubeErrorPx(camera, truth, behind), 1e6);
}

TEST(RelocalisationExperiment, TrackedFrameTimingKeepsTrackedFramesOfEachTracker) {
  std::vector<cv::Mat> frames(7, cv::Mat::zeros(4, 4, CV_8UC1));
  int firstCalls = 0;
  std::vector<int> order;
  const FrameTracker everyFrame = [&](const cv::Mat&) -> std::optional<RigidPose> {
    ++firstCalls;
    order.push_back(1);
    return RigidPose();
  };
  int secondCalls = 0;
  const FrameTracker everyOther = [&](const cv::Mat&) -> std::optional<RigidPose> {
    order.push_back(2);
    if (secondCalls++ % 2 == 0) return RigidPose();
    return std::nullopt;
  };
  const TrackedFrameTiming t = compareTrackedFrameMs(frames, everyFrame, everyOther);
  EXPECT_EQ(firstCalls, 7);
  EXPECT_EQ(secondCalls, 7);
  EXPECT_EQ(t.msFirst.size(), 7u);
  EXPECT_EQ(t.msSecond.size(), 4u);  // frames 0, 2, 4, 6
  for (double ms : t.msFirst) EXPECT_GE(ms, 0.0);
  // They take turns at going first.
  ASSERT_EQ(order.size(), 14u);
  EXPECT_EQ(order[0], 1);
  EXPECT_EQ(order[2], 2);
  EXPECT_EQ(order[4], 1);
}

TEST(RelocalisationExperiment, OptionsCheckNamesTheBadField) {
  RelocalisationExperimentOptions o;
  EXPECT_NO_THROW(o.check());
  o.coldStarts = -1;
  EXPECT_THROW(o.check(), Error);
  o = {};
  o.wrongPx = 1.0;  // below successPx
  EXPECT_THROW(o.check(), Error);
  o = {};
  o.views.maxAngleDeg = 120;
  EXPECT_THROW(o.check(), Error);
}

// Issue 13's cold start and kidnapped camera on small samples, against the simulator's exact
// poses: 20 cold starts and 10 kidnaps over the 6-reference walkaround map. A wrong pose (cube
// error > 5 px) is never acceptable: none asserted. The bounds are the rate target
// (>= 95% good, i.e. >= 17 of 20 and >= 8 of 10 at a 1.6% / 8.6% chance of falling below with a
// true 95%); this seed measures 19/20 cold starts and 9/10 kidnaps good (17/20 before the SQPnP
// re-estimate and the references' finer ORB levels, 2026-12-01).
TEST(RelocalisationExperiment, ColdStartAndKidnappedCameraOnSmallSamples) {
  WalkaroundSixReferences w;
  SceneSimulator& sim = w.sim;
  const TrackerParams& params = w.params;
  const MultiReferenceMap& map = w.map;
  RelocalisationExperimentOptions e;
  e.coldStarts = 20;
  e.kidnaps = 10;
  e.baseline = false;
  const RelocalisationExperimentResult r = runRelocalisationExperiment(
      sim, map, [&] { return multiReferenceFrameTracker(map, params); }, e);
  const RateSummary cold = r.coldStart(), kidnap = r.kidnap();
  std::cout << "cold start " << cold.good << "/" << cold.trials << " good, " << cold.wrong
            << " wrong, median " << r.medianColdStartMs() << " ms (relocaliser "
            << r.medianRelocaliseMs() << " ms wall, " << r.medianRelocaliseCpuMs()
            << " ms CPU); kidnapped " << kidnap.good << "/" << kidnap.trials << ", " << kidnap.wrong
            << " wrong\n";
  // Every cold start is a fresh tracker: its first frame tries the paper's start near a reference,
  // then (when that fails) a relocalisation attempt, timed; a frame without either was posed by
  // the start, and a frame without a pose says why.
  int attempts = 0;
  for (const ColdStartTrial& t : r.coldStarts) {
    if (t.relocaliseMs >= 0.0) {
      ++attempts;
      EXPECT_GE(t.relocaliseCpuMs, 0.0);
      // Process CPU (OpenCV's workers included): about the wall time on each core there is at
      // most. Not tighter: the process clock also counts OpenCV's workers still spinning after an
      // earlier parallel region, and a fresh clone's CI on a shared 2-core host measured 77.9 ms
      // of CPU in 35.1 ms of wall time. The bound catches a wrong unit or clock, not a speed.
      EXPECT_LE(t.relocaliseCpuMs,
                1.5 * t.relocaliseMs *
                        std::max(1, static_cast<int>(std::thread::hardware_concurrency())) +
                    5.0);
    } else {
      EXPECT_TRUE(t.posed) << t.trackerMessage;
    }
    if (!t.posed) {
      EXPECT_FALSE(t.trackerMessage.empty());
    }
  }
  EXPECT_GT(attempts, 0);
  EXPECT_GE(cold.good, 17);
  EXPECT_EQ(cold.wrong, 0);
  EXPECT_GE(kidnap.good, 8);
  EXPECT_EQ(kidnap.wrong, 0);
}

// The cause of most close-view cold-start failures (issue 13, 200 views of 8 references: 5 of
// the 15 failures at 0.5-0.6x the reference distance): such a view sees finer keypoints than the
// reference's finest ORB level (now 3 upsampled levels finer) and, near a plane, solvePnPRansac's
// EPnP re-estimate kept a few of its inliers (now SQPnP). 12 random views at 0.5-0.65x over the
// 6-reference walkaround map: at least 11 of 12 good and none wrong (the 95%: 11/12
// holds 88% of the time at a true 95%).
TEST(RelocalisationExperiment, CloseViewsColdStart) {
  WalkaroundSixReferences w;
  SceneSimulator& sim = w.sim;
  const TrackerParams& params = w.params;
  const MultiReferenceMap& map = w.map;
  RelocalisationExperimentOptions e;
  e.coldStarts = 12;
  e.kidnaps = 0;
  e.baseline = false;
  e.seed = 5;
  e.views.minDistanceRatio = 0.5;
  e.views.maxDistanceRatio = 0.65;
  const RateSummary cold = runRelocalisationExperiment(
                               sim, map, [&] { return multiReferenceFrameTracker(map, params); }, e)
                               .coldStart();
  std::cout << "close views (0.5-0.65x): " << cold.good << "/" << cold.trials << " good, "
            << cold.wrong << " wrong\n";
  EXPECT_GE(cold.good, 11);
  EXPECT_EQ(cold.wrong, 0);
}
