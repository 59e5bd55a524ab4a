// interpolateTrajectory: exact at samples, linear centre + slerp between them, nothing outside
// the trajectory or across gaps.
#include "engine/evaluation/TrajectoryInterpolation.hpp"

#include <gtest/gtest.h>

#include "engine/core/Error.hpp"

using namespace reftrack;

namespace {

// Camera moving at constant velocity and turning at a constant rate about a fixed axis: linear
// interpolation of the centre and slerp of the orientation reproduce it exactly.
RigidPose poseAt(double t) {
  const Eigen::Vector3d c(0.2 * t, -0.1 * t, 0.5);
  const Eigen::Quaterniond q(Eigen::AngleAxisd(0.3 * t, Eigen::Vector3d(1, 2, 3).normalized()));
  return RigidPose(q, c).inverse();  // camera-in-world -> world->camera
}

}  // namespace

TEST(TrajectoryInterpolation, ReproducesUniformMotionBetweenSamples) {
  TumTrajectory samples;
  for (int k = 10; k >= 0; --k) samples.poses.push_back({0.01 * k, poseAt(0.01 * k)});  // unsorted
  const TumTrajectory out = interpolateTrajectory(samples, {0.0333, 0.05, -0.01, 0.2, 0.0}, 0.02);
  // -0.01 and 0.2 lie outside the samples: no pose; order of the others kept.
  ASSERT_EQ(out.poses.size(), 3u);
  EXPECT_DOUBLE_EQ(out.poses[0].timestamp, 0.0333);
  EXPECT_DOUBLE_EQ(out.poses[1].timestamp, 0.05);
  EXPECT_DOUBLE_EQ(out.poses[2].timestamp, 0.0);
  for (const StampedPose& p : out.poses) {
    const RigidPose truth = poseAt(p.timestamp);
    EXPECT_LT(RigidPose::translationDistance(p.worldToCamera, truth), 1e-12) << p.timestamp;
    EXPECT_LT(RigidPose::rotationDistance(p.worldToCamera, truth), 1e-9) << p.timestamp;
  }
}

TEST(TrajectoryInterpolation, NoPoseAcrossAGapLongerThanMaxGap) {
  TumTrajectory samples;
  for (double t : {0.0, 0.01, 0.5, 0.51}) samples.poses.push_back({t, poseAt(t)});
  EXPECT_EQ(interpolateTrajectory(samples, {0.005, 0.3, 0.505}, 0.05).poses.size(), 2u);
  EXPECT_EQ(interpolateTrajectory(samples, {0.005, 0.3, 0.505}, 1.0).poses.size(), 3u);
  EXPECT_THROW(interpolateTrajectory(samples, {0.0}, -1.0), Error);
}
