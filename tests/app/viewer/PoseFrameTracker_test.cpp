#include "app/viewer/PoseFrameTracker.hpp"

#include <gtest/gtest.h>

#include "engine/tracking/PlaneWorld.hpp"

namespace reftrack::app {
namespace {

// The adapter hands the viewer the pose, status, timings and debug layers; the epipolar lines it
// draws must pass through the frame positions of the V_A matches they belong to (< 1 px: the
// matches are RANSAC inliers with a 2.5 px gate at 320x240, i.e. ~5 px at 640x480, but most sit
// within a fraction of a pixel).
TEST(PoseFrameTracker, ReportsPoseTimingsAndConsistentDebugLayers) {
  const test::PlaneWorld world;
  PoseFrameTracker tracker(world.map(), TrackerParams{});
  TrackingResult r;
  for (int k = 0; k < 5; ++k) r = tracker.process(world.render(test::pathPose(k), k), k, k / 30.0);
  ASSERT_TRUE(r.worldToCamera.has_value());
  EXPECT_EQ(r.status, "tracking");
  EXPECT_FALSE(r.stages.empty());
  EXPECT_GT(r.inliers, 20);
  EXPECT_FALSE(r.debug.corners.empty());
  ASSERT_FALSE(r.debug.epipolarLines.empty());
  std::vector<double> distances;
  for (const cv::Vec3d& l : r.debug.epipolarLines) {
    double best = 1e9;
    for (const auto& m : r.debug.matches)
      best = std::min(
          best, std::abs(l[0] * m.second.x + l[1] * m.second.y + l[2]) / std::hypot(l[0], l[1]));
    distances.push_back(best);
  }
  std::sort(distances.begin(), distances.end());
  EXPECT_LT(distances[distances.size() / 2], 1.0);
}

// The predicted overlay error of the object the viewer draws; above pose.max_predicted_error_px
// the status is "uncertain: <why>" and the pose is still given (drawn dimmed).
TEST(PoseFrameTracker, ReportsThePredictedErrorAndUncertainFrames) {
  const test::PlaneWorld world;
  TrackerParams params;
  params.pose.maxPredictedErrorPx = 1e-4;
  PoseFrameTracker tracker(world.map(), params);
  const std::vector<Eigen::Vector3d> cube = {{0, 0, 0}, {0.05, 0, 0}, {0, 0.05, 0}, {0, 0, 0.05}};
  tracker.setOverlayPoints(cube);
  EXPECT_EQ(tracker.tracker().overlayPoints(), cube);
  TrackingResult r;
  for (int k = 0; k < 3; ++k) r = tracker.process(world.render(test::pathPose(k), k), k, k / 30.0);
  ASSERT_TRUE(r.worldToCamera.has_value()) << r.status;
  ASSERT_TRUE(r.predictedErrorPx.has_value());
  EXPECT_GT(*r.predictedErrorPx, 1e-4);
  EXPECT_TRUE(r.uncertain);
  EXPECT_EQ(r.status.rfind("uncertain: predicted overlay error", 0), 0u) << r.status;
  params.pose.maxPredictedErrorPx = 0.0;  // off
  tracker.applyParams(params);
  r = tracker.process(world.render(test::pathPose(3), 3), 3, 3 / 30.0);
  EXPECT_FALSE(r.uncertain);
  EXPECT_EQ(r.status, "tracking");
  EXPECT_TRUE(r.predictedErrorPx.has_value());
}

TEST(PoseFrameTracker, ABlackFrameIsReportedLostWithItsReason) {
  const test::PlaneWorld world;
  PoseFrameTracker tracker(world.map(), TrackerParams{});
  const TrackingResult r = tracker.process(cv::Mat(world.size, CV_8UC3, cv::Scalar(0, 0, 0)), 0, 0);
  EXPECT_FALSE(r.worldToCamera.has_value());
  EXPECT_NE(r.status.find("lost"), std::string::npos) << r.status;
}

}  // namespace
}  // namespace reftrack::app
