#include "engine/geometry/FundamentalMatrix.hpp"

#include <gtest/gtest.h>

namespace reftrack {
namespace {

// Projections of any 3D point into the two cameras satisfy p2^T F p1 = 0 (to rounding).
TEST(FundamentalMatrix, CorrespondingPixelsSatisfyTheEpipolarConstraint) {
  Eigen::Matrix3d K;
  K << 500, 0, 320, 0, 510, 240, 0, 0, 1;
  const RigidPose T =
      RigidPose::fromVector6((Vector6d() << 0.2, -0.05, 0.03, 0.05, -0.1, 0.02).finished());
  const Eigen::Matrix3d F = fundamentalMatrix(K, T);
  for (const Eigen::Vector3d& X : {Eigen::Vector3d(0.1, 0.2, 1.5), Eigen::Vector3d(-0.3, 0.1, 2.0),
                                   Eigen::Vector3d(0.0, -0.2, 0.8)}) {
    const Eigen::Vector3d p1 = K * X / X.z();
    const Eigen::Vector3d X2 = T * X;
    const Eigen::Vector3d p2 = K * X2 / X2.z();
    EXPECT_NEAR(p2.dot(F * p1) / (F * p1).head<2>().norm(), 0.0, 1e-9);
  }
  EXPECT_NEAR((skewSymmetric(Eigen::Vector3d(1, 2, 3)) * Eigen::Vector3d(1, 2, 3)).norm(), 0.0,
              1e-12);
}

}  // namespace
}  // namespace reftrack
