// Tests for EpipolarDistanceCost and ThreeViewReprojectionCost (header-only cost functors).
#include <ceres/gradient_checker.h>
#include <gtest/gtest.h>

#include <opencv2/calib3d.hpp>
#include <random>

#include "engine/estimation/EpipolarDistanceCost.hpp"
#include "engine/estimation/ThreeViewReprojectionCost.hpp"

using namespace reftrack;

namespace {

struct Scene {
  Eigen::Matrix3d K;
  RigidPose T_AB, T_Ak;
  Scene() {
    K << 520, 0, 320, 0, 525, 240, 0, 0, 1;
    T_AB = RigidPose::fromVector6((Vector6d() << -0.25, 0.02, 0.03, 0.03, -0.2, 0.02).finished());
    T_Ak = RigidPose::fromVector6((Vector6d() << 0.08, -0.03, 0.05, -0.06, 0.1, 0.04).finished());
  }
  Eigen::Vector2d project(const RigidPose& T, const Eigen::Vector3d& P) const {
    const Eigen::Vector3d q = K * (T * P);
    return q.head<2>() / q.z();
  }
};

bool gradientsAgree(ceres::CostFunction* cost, const Vector6d& at) {
  std::unique_ptr<ceres::CostFunction> owned(cost);
  ceres::NumericDiffOptions options;
  const std::vector<const ceres::Manifold*>* noManifolds = nullptr;
  ceres::GradientChecker checker(cost, noManifolds, options);
  double x[6];
  for (int i = 0; i < 6; ++i) x[i] = at[i];
  double* params[] = {x};
  ceres::GradientChecker::ProbeResults results;
  const bool ok = checker.Probe(params, 1e-6, &results);
  if (!ok) ADD_FAILURE() << results.error_log;
  return ok;
}

}  // namespace

TEST(EpipolarDistanceCost, ZeroForExactMatchesOfBothReferences) {
  const Scene s;
  const Vector6d x = s.T_Ak.toVector6();
  const Eigen::Vector3d P(0.1, -0.05, 1.1);
  for (const RigidPose& refToA : {RigidPose(), s.T_AB.inverse()}) {
    const Eigen::Vector2d pRef = s.project(refToA.inverse(), P), pK = s.project(s.T_Ak, P);
    EpipolarDistanceCost cost(s.K, refToA, pRef, pK, 1.0);
    double r[2];
    cost(x.data(), r);
    EXPECT_NEAR(r[0], 0.0, 1e-9);
    EXPECT_NEAR(r[1], 0.0, 1e-9);
  }
}

TEST(EpipolarDistanceCost, EqualsPerpendicularDistanceToOpenCvEpiline) {
  const Scene s;
  const Vector6d x = s.T_Ak.toVector6();
  const Eigen::Vector3d P(-0.2, 0.1, 1.4);
  const Eigen::Vector2d pA = s.project(RigidPose(), P);
  const Eigen::Vector2d pK = s.project(s.T_Ak, P) + Eigen::Vector2d(1.5, -2.0);  // off the line
  EpipolarDistanceCost cost(s.K, RigidPose(), pA, pK, 0.5);
  double r[2];
  cost(x.data(), r);
  // Independent: F from the pose, the epiline of p_A in the current frame by OpenCV.
  const Eigen::Matrix3d R = s.T_Ak.rotation();
  const Eigen::Vector3d t = s.T_Ak.translation();
  Eigen::Matrix3d tx;
  tx << 0, -t.z(), t.y(), t.z(), 0, -t.x(), -t.y(), t.x(), 0;
  const Eigen::Matrix3d F = s.K.inverse().transpose() * tx * R * s.K.inverse();
  cv::Matx33d Fcv;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) Fcv(i, j) = F(i, j);
  std::vector<cv::Vec3d> lines;
  cv::computeCorrespondEpilines(std::vector<cv::Point2d>{{pA.x(), pA.y()}}, 1, Fcv, lines);
  const double d = lines[0][0] * pK.x() + lines[0][1] * pK.y() + lines[0][2];  // normalised line
  EXPECT_NEAR(std::abs(r[0]) * 0.5, std::abs(d), 1e-9);  // residual is divided by sigma = 0.5
}

TEST(EpipolarDistanceCost, AnalyticJetsMatchNumericDerivatives) {
  const Scene s;
  const Eigen::Vector3d P(0.05, 0.02, 0.9);
  gradientsAgree(
      EpipolarDistanceCost::create(s.K, s.T_AB.inverse(), s.project(s.T_AB, P),
                                   s.project(s.T_Ak, P) + Eigen::Vector2d(0.3, 0.2), 0.4),
      s.T_Ak.toVector6());
}

TEST(ThreeViewReprojectionCost, ZeroAtTruthAndDerivativesCheck) {
  const Scene s;
  const Eigen::Vector3d P(0.1, 0.2, 1.3);
  ThreeViewReprojectionCost cost(s.K, P, s.project(s.T_Ak, P), 0.4);
  double r[2];
  cost(s.T_Ak.toVector6().data(), r);
  EXPECT_NEAR(r[0], 0.0, 1e-9);
  EXPECT_NEAR(r[1], 0.0, 1e-9);
  gradientsAgree(
      ThreeViewReprojectionCost::create(s.K, P, s.project(s.T_Ak, P) + Eigen::Vector2d(1, -1), 0.4),
      s.T_Ak.toVector6());
}
