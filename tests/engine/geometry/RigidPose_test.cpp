#include "engine/geometry/RigidPose.hpp"

#include <gtest/gtest.h>

#include <opencv2/calib3d.hpp>
#include <random>

using namespace reftrack;

TEST(RigidPose, Vector6RoundTripMatchesRodrigues) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-2.0, 2.0);
  for (int i = 0; i < 100; ++i) {
    Vector6d x;
    for (int k = 0; k < 6; ++k) x[k] = u(rng);
    const RigidPose T = RigidPose::fromVector6(x);
    // Same rotation as OpenCV's Rodrigues (the SPEC's axis-angle).
    cv::Matx33d Rcv;
    cv::Rodrigues(cv::Vec3d(x[3], x[4], x[5]), Rcv);
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(T.rotation()(r, c), Rcv(r, c), 1e-12);
    const Vector6d back = T.toVector6();
    if (x.tail<3>().norm() < 3.1) {
      EXPECT_LT((back - x).norm(), 1e-9);
    }
    EXPECT_LT((RigidPose::fromVector6(back).matrix4() - T.matrix4()).norm(), 1e-9);
  }
}

TEST(RigidPose, CompositionFollowsSpecConventions) {
  // T_k = T_Ak * T_A: apply T_A first.
  const RigidPose TA =
      RigidPose::fromVector6((Vector6d() << 0.1, -0.2, 1.0, 0.1, 0.2, -0.3).finished());
  const RigidPose TAk =
      RigidPose::fromVector6((Vector6d() << -0.05, 0.0, 0.02, 0.0, 0.1, 0.05).finished());
  const Eigen::Vector3d X(0.3, -0.1, 0.2);
  EXPECT_LT(((TAk * TA) * X - TAk * (TA * X)).norm(), 1e-12);
  EXPECT_LT(((TA.inverse() * TA) * X - X).norm(), 1e-12);
  // T_AB = T_B * T_A^-1 maps camera A points to camera B.
  const RigidPose TB = TAk * TA;
  const RigidPose TAB = TB * TA.inverse();
  EXPECT_LT((TAB * (TA * X) - TB * X).norm(), 1e-12);
  EXPECT_LT((TA.cameraCentre() - TA.inverse().translation()).norm(), 1e-12);
}

TEST(RigidPose, DistancesMeasureDegreesAndMetres) {
  const RigidPose a;
  const RigidPose b =
      RigidPose::fromVector6((Vector6d() << 0.003, 0.004, 0, 0, 0, 0.01).finished());
  EXPECT_NEAR(RigidPose::translationDistance(a, b), 0.005, 1e-12);
  EXPECT_NEAR(RigidPose::rotationDistance(a, b), 0.01, 1e-12);
}

TEST(RigidPose, RejectsNonRigid4x4) {
  Eigen::Matrix4d T = Eigen::Matrix4d::Identity();
  T(3, 0) = 1.0;
  EXPECT_THROW(RigidPose::fromMatrix4(T), std::runtime_error);
}
