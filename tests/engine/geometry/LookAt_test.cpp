#include "engine/geometry/LookAt.hpp"

#include <gtest/gtest.h>

#include "engine/core/Error.hpp"
#include "engine/geometry/PinholeCamera.hpp"

using namespace reftrack;

TEST(LookAt, TargetProjectsToThePrincipalPointWithUpAtTheTop) {
  const PinholeCamera cam = PinholeCamera::fromFieldOfView({640, 480}, 60.0);
  const Eigen::Vector3d eye(-0.3, -0.6, 0.8), target(0.1, 0.2, 0.05);
  const RigidPose pose = lookAtPose(eye, target);
  // Pure arithmetic on unit vectors: only rounding error remains.
  EXPECT_LT((pose.rotation() * pose.rotation().transpose() - Eigen::Matrix3d::Identity()).norm(),
            1e-12);
  EXPECT_NEAR(pose.rotation().determinant(), 1.0, 1e-12);
  EXPECT_LT((pose.cameraCentre() - eye).norm(), 1e-12);
  const Eigen::Vector2d centre = cam.project(pose, target);
  EXPECT_NEAR(centre.x(), cam.cx(), 1e-9);
  EXPECT_NEAR(centre.y(), cam.cy(), 1e-9);
  // A point above the target appears above it (smaller image y); the camera x axis is level.
  EXPECT_LT(cam.project(pose, target + Eigen::Vector3d(0, 0, 0.1)).y(), centre.y());
  EXPECT_NEAR(pose.rotation().row(0).z(), 0.0, 1e-12);
  // Looking down at the desk: camera z opposes the desk normal.
  EXPECT_LT(pose.rotation().row(2).z(), 0.0);
}

TEST(LookAt, DegenerateViewsThrow) {
  EXPECT_THROW(lookAtPose({1, 2, 3}, {1, 2, 3}), Error);
  EXPECT_THROW(lookAtPose({0, 0, 1}, {0, 0, 0}), Error);  // straight down, parallel to up
}
