#include "app/simulator/WalkaroundArc.hpp"

#include <gtest/gtest.h>

#include <cmath>

using namespace reftrack::app;

TEST(WalkaroundArc, PositionAndEyeRoundTrip) {
  const Eigen::Vector3d target(0.0, 0.2, 0.06);
  for (const Eigen::Vector3d& eye :
       {Eigen::Vector3d(-0.125, -0.52, 0.74), Eigen::Vector3d(0.9, 0.1, 0.3),
        Eigen::Vector3d(-0.5, 0.8, 1.5)}) {
    const ArcPosition p = WalkaroundArc::positionOf(eye, target);
    EXPECT_LT((WalkaroundArc::eyeAt(p, target) - eye).norm(), 1e-12);
    EXPECT_NEAR(p.distance, (eye - target).norm(), 1e-12);
  }
  // Reference view A of the desk scene: slightly left of the front, 1.0 m away, 43 deg up.
  const ArcPosition a = WalkaroundArc::positionOf({-0.125, -0.52, 0.74}, target);
  EXPECT_NEAR(a.azimuthRad * 180.0 / M_PI, -9.85, 0.01);
  EXPECT_NEAR(a.distance, 0.998, 0.001);
  EXPECT_NEAR(a.elevationRad * 180.0 / M_PI, 42.94, 0.01);
  // Azimuth 0 is in front (-y), +90 deg is on the +x side, elevation 90 deg straight above.
  EXPECT_LT((WalkaroundArc::eyeAt({0.0, 1.0, 0.0}, target) - Eigen::Vector3d(0, -0.8, 0.06)).norm(),
            1e-12);
  EXPECT_LT(
      (WalkaroundArc::eyeAt({M_PI / 2, 1.0, 0.0}, target) - Eigen::Vector3d(1, 0.2, 0.06)).norm(),
      1e-12);
  EXPECT_LT(
      (WalkaroundArc::eyeAt({0.3, 1.0, M_PI / 2}, target) - Eigen::Vector3d(0, 0.2, 1.06)).norm(),
      1e-12);
}
