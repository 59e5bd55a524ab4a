// TrajectoryReplayTracker: the stored pose of each frame, by timestamp or index; "lost" without.
#include "app/viewer/TrajectoryReplayTracker.hpp"

#include <gtest/gtest.h>

#include "TestPaths.hpp"
#include "engine/core/Error.hpp"

using namespace reftrack;
using namespace reftrack::app;

namespace {

RigidPose poseNumber(int k) {
  return RigidPose(rotationFromAxisAngle(Eigen::Vector3d(0.01 * k, 0.02, 0)),
                   Eigen::Vector3d(0.1 * k, 0, 1));
}

}  // namespace

TEST(TrajectoryReplayTracker, ReplaysByTimestampThenIndex) {
  TumTrajectory t;
  for (int k = 0; k < 5; ++k) t.poses.push_back({10.0 + k / 30.0, poseNumber(k)});
  TrajectoryReplayTracker tracker(t, 30.0);
  const cv::Mat frame(4, 4, CV_8UC3);
  // Timestamp within half a frame period selects the pose.
  TrackingResult r = tracker.process(frame, 99, 10.0 + 2 / 30.0 + 0.01);
  ASSERT_TRUE(r.worldToCamera);
  EXPECT_EQ(r.status, "tracking");
  EXPECT_LT(RigidPose::translationDistance(*r.worldToCamera, poseNumber(2)), 1e-12);
  ASSERT_EQ(r.stages.size(), 1u);
  EXPECT_EQ(r.stages[0].name, "replay");
  // Timestamps from another clock: the frame index picks the pose.
  r = tracker.process(frame, 4, 0.0);
  ASSERT_TRUE(r.worldToCamera);
  EXPECT_LT(RigidPose::translationDistance(*r.worldToCamera, poseNumber(4)), 1e-12);
  // Neither: lost.
  r = tracker.process(frame, 5, 0.0);
  EXPECT_FALSE(r.worldToCamera);
  EXPECT_EQ(r.status, "lost");
}

TEST(TrajectoryReplayTracker, LoadsATumFileAndRejectsBadInput) {
  const auto dir = test::freshTempDir("TrajectoryReplayTracker_Load");
  TumTrajectory t;
  t.poses.push_back({0.0, poseNumber(1)});
  t.save(dir / "t.txt");
  TrajectoryReplayTracker tracker = TrajectoryReplayTracker::load(dir / "t.txt", 30.0);
  const TrackingResult r = tracker.process(cv::Mat(), 0, 0.0);
  ASSERT_TRUE(r.worldToCamera);
  // The TUM file stores camera-in-world; the tracker returns world->camera again.
  EXPECT_LT(RigidPose::rotationDistance(*r.worldToCamera, poseNumber(1)), 1e-9);
  EXPECT_THROW(TrajectoryReplayTracker(TumTrajectory{}, 30.0), Error);
  EXPECT_THROW(TrajectoryReplayTracker(t, 0.0), Error);
  EXPECT_THROW(TrajectoryReplayTracker::load(dir / "missing.txt", 30.0), Error);
  TrackerParams bad;
  bad.ransac.maxIterations = -1;
  EXPECT_THROW(tracker.applyParams(bad), Error);
  EXPECT_NO_THROW(tracker.applyParams(TrackerParams{}));
}
