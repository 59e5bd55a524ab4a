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

TEST(PoseFrameTracker, ABlackFrameIsReportedLostWithItsReason) {
  const test::PlaneWorld world;
  PoseFrameTracker tracker(world.map(), TrackerParams{});
  const TrackingResult r = tracker.process(cv::Mat(world.size, CV_8UC3, cv::Scalar(0, 0, 0)), 0, 0);
  EXPECT_FALSE(r.worldToCamera.has_value());
  EXPECT_NE(r.status.find("lost"), std::string::npos) << r.status;
}

}  // namespace
}  // namespace reftrack::app
