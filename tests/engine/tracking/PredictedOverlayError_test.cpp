#include "engine/tracking/PredictedOverlayError.hpp"

#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <cmath>
#include <limits>
#include <random>

#include "ErrorMessage.hpp"

namespace reftrack {
namespace {

// A 640x480 camera (f = 500 px) 1 m in front of a 0.2 m cube, turned by a rotation vector of
// 0.3 rad so that r is far from 0 (where d(R(r) X)/dr would be the simple -[X]x).
const PinholeCamera kCamera((Eigen::Matrix3d() << 500, 0, 320, 0, 510, 240, 0, 0, 1).finished(),
                            {640, 480});

RigidPose cameraPose() {
  Vector6d x;
  x << 0.05, -0.03, 1.0, 0.1, -0.25, 0.12;
  return RigidPose::fromVector6(x);
}

std::vector<Eigen::Vector3d> cube(double edge) {
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i < 8; ++i)
    points.emplace_back(i & 1 ? edge / 2 : -edge / 2, i & 2 ? edge / 2 : -edge / 2,
                        i & 4 ? edge : 0.0);
  return points;
}

// A full covariance of (t, r): SDs of 2 / 1 / 4 mm and 2 / 3 / 1 mrad, correlated.
Matrix6d poseCovariance() {
  Matrix6d A;
  A << 1.0, 0.2, 0.0, 0.1, 0.0, 0.3,  //
      0.0, 0.5, 0.1, 0.0, 0.2, 0.0,   //
      0.3, 0.0, 2.0, 0.0, 0.1, 0.0,   //
      0.0, 0.1, 0.0, 1.0, 0.0, 0.2,   //
      0.2, 0.0, 0.0, 0.3, 1.5, 0.0,   //
      0.0, 0.0, 0.1, 0.0, 0.2, 0.5;
  const Vector6d sd = (Vector6d() << 0.002, 0.001, 0.004, 0.002, 0.003, 0.001).finished();
  const Matrix6d C = A * A.transpose();
  const Vector6d scale = sd.cwiseQuotient(C.diagonal().cwiseSqrt());
  return scale.asDiagonal() * C * scale.asDiagonal();
}

// RMS over points and samples of the displacement of the projected points when the pose
// 6-vector is drawn from N(pose, covariance).
double monteCarloRmsPx(const RigidPose& pose, const Matrix6d& covariance,
                       const std::vector<Eigen::Vector3d>& points, int samples) {
  const Matrix6d L = covariance.llt().matrixL();
  std::mt19937_64 rng(42);
  std::normal_distribution<double> normal;
  const Vector6d x = pose.toVector6();
  double sum = 0.0;
  for (int s = 0; s < samples; ++s) {
    Vector6d z;
    for (int i = 0; i < 6; ++i) z[i] = normal(rng);
    const RigidPose drawn = RigidPose::fromVector6(x + L * z);
    for (const Eigen::Vector3d& X : points)
      sum += (kCamera.project(drawn * X) - kCamera.project(pose * X)).squaredNorm();
  }
  return std::sqrt(sum / (static_cast<double>(samples) * static_cast<double>(points.size())));
}

TEST(PredictedOverlayError, JacobianMatchesCentralDifferences) {
  const RigidPose pose = cameraPose();
  const Eigen::Vector3d X(0.07, -0.04, 0.1);
  const Eigen::Matrix<double, 2, 6> J = projectionJacobian(kCamera, pose, X);
  const Vector6d x = pose.toVector6();
  const double h = 1e-6;
  for (int i = 0; i < 6; ++i) {
    Vector6d plus = x, minus = x;
    plus[i] += h;
    minus[i] -= h;
    const Eigen::Vector2d numeric = (kCamera.project(RigidPose::fromVector6(plus) * X) -
                                     kCamera.project(RigidPose::fromVector6(minus) * X)) /
                                    (2 * h);
    // Central differences at h = 1e-6 of pixels ~500 px per unit: ~1e-6 px of rounding.
    EXPECT_LT((J.col(i) - numeric).norm(), 1e-4 * (1.0 + numeric.norm())) << i;
  }
}

// The prediction is the first-order RMS displacement: Monte-Carlo sampling of the covariance
// (20000 poses) agrees within 2%. Tolerance: |d|^2 of a 2-D Gaussian has a relative SD of at most
// ~1.4, so the sampled mean square is good to ~1% (1.4 / sqrt(20000)) and its root to ~0.5%; the
// linearisation error at milliradian SDs is ~1e-3 relative. The prediction with the covariance's
// t and r blocks exchanged (the wrong order) is far off the same samples.
TEST(PredictedOverlayError, AgreesWithMonteCarloSamplingOfTheCovariance) {
  const RigidPose pose = cameraPose();
  const Matrix6d covariance = poseCovariance();
  const std::vector<Eigen::Vector3d> points = cube(0.2);
  const std::optional<double> predicted =
      predictedOverlayErrorPx(kCamera, pose, covariance, points);
  ASSERT_TRUE(predicted);
  const double sampled = monteCarloRmsPx(pose, covariance, points, 20000);
  EXPECT_NEAR(*predicted / sampled, 1.0, 0.02) << *predicted << " vs " << sampled;
  EXPECT_GT(*predicted, 1.0);  // a few pixels: the figures are not trivially small
  Matrix6d swapped;
  swapped << covariance.bottomRightCorner<3, 3>(), covariance.bottomLeftCorner<3, 3>(),
      covariance.topRightCorner<3, 3>(), covariance.topLeftCorner<3, 3>();
  const double wrong = *predictedOverlayErrorPx(kCamera, pose, swapped, points);
  EXPECT_GT(std::abs(wrong / sampled - 1.0), 0.2) << wrong << " vs " << sampled;
  RecordProperty("predicted_px", std::to_string(*predicted));
  RecordProperty("monte_carlo_px", std::to_string(sampled));
}

// Omega_k of x_Ak with the points in camera A's frame, and the same covariance carried to the
// world -> camera 6-vector (J Omega J^T, J by central differences) with world points: the same
// prediction to first order — what checkPredictedOverlayError relies on.
TEST(PredictedOverlayError, RelativeAndWorldParameterisationsAgree) {
  const RigidPose T_A =
      RigidPose::fromVector6((Vector6d() << -0.1, 0.02, 0.9, 0.05, 0.2, -0.1).finished());
  const RigidPose T_Ak =
      RigidPose::fromVector6((Vector6d() << 0.08, -0.01, 0.05, -0.02, 0.15, 0.04).finished());
  const RigidPose T_k = T_Ak * T_A;
  const Matrix6d omega = poseCovariance();
  const std::vector<Eigen::Vector3d> world = cube(0.1);
  const Vector6d x = T_Ak.toVector6();
  Matrix6d J;
  const double h = 1e-6;
  for (int i = 0; i < 6; ++i) {
    Vector6d plus = x, minus = x;
    plus[i] += h;
    minus[i] -= h;
    J.col(i) = ((RigidPose::fromVector6(plus) * T_A).toVector6() -
                (RigidPose::fromVector6(minus) * T_A).toVector6()) /
               (2 * h);
  }
  const double inWorld = *predictedOverlayErrorPx(kCamera, T_k, J * omega * J.transpose(), world);
  PoseTrackingResult tracked;
  tracked.state = TrackingState::Tracking;
  tracked.worldToCamera = T_k;
  tracked.T_Ak = T_Ak;
  tracked.covariance = omega;
  const OverlayErrorCheck check = checkPredictedOverlayError(kCamera, tracked, world, PoseParams{});
  ASSERT_TRUE(check.predictedErrorPx);
  EXPECT_NEAR(*check.predictedErrorPx / PoseParams{}.predictedErrorScale, inWorld, 1e-6 * inWorld);
}

TEST(PredictedOverlayError, PointsBehindTheCameraAreSkipped) {
  const RigidPose pose = cameraPose();
  const Matrix6d covariance = poseCovariance();
  std::vector<Eigen::Vector3d> points = cube(0.2);
  const double inFront = *predictedOverlayErrorPx(kCamera, pose, covariance, points);
  points.push_back(pose.inverse() * Eigen::Vector3d(0.1, 0.1, -1.0));  // behind the camera
  EXPECT_DOUBLE_EQ(*predictedOverlayErrorPx(kCamera, pose, covariance, points), inFront);
  EXPECT_FALSE(predictedOverlayErrorPx(kCamera, pose, covariance,
                                       {pose.inverse() * Eigen::Vector3d(0, 0, -2.0)}));
  EXPECT_FALSE(predictedOverlayErrorPx(kCamera, pose, covariance, {}));
  EXPECT_DOUBLE_EQ(*predictedOverlayErrorPx(kCamera, pose, Matrix6d::Zero(), points), 0.0);
  Matrix6d bad = covariance;
  bad(2, 2) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_NE(test::errorMessage([&] {
              predictedOverlayErrorPx(kCamera, pose, bad, points);
            }).find("not finite"),
            std::string::npos);
}

// A camera moved 1 mm sideways shifts every point at 1 m depth by f * 1 mm = 0.5 px.
TEST(PredictedOverlayError, TrueErrorIsTheMeanPointDistance) {
  const RigidPose truth;
  const RigidPose estimate(Eigen::Matrix3d::Identity(), Eigen::Vector3d(0.001, 0, 0));
  const std::vector<Eigen::Vector3d> points = {{0, 0, 1}, {0.1, 0.1, 1}, {-0.2, 0.1, 1}};
  EXPECT_NEAR(*overlayErrorPx(kCamera, truth, estimate, points), 0.5, 1e-12);
  EXPECT_FALSE(overlayErrorPx(kCamera, truth, estimate, {{0, 0, -1}}));
}

TEST(PredictedOverlayError, TheDefaultObjectIsTheBoxOfTheCentralMapPoints) {
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i <= 100; ++i) points.emplace_back(0.01 * i, -0.002 * i, 0.0005 * i);
  points.emplace_back(50.0, 50.0, 50.0);  // a stray point far away is left out
  const std::vector<Eigen::Vector3d> box = centralBoxCorners(points);
  ASSERT_EQ(box.size(), 8u);
  EXPECT_NEAR(box[0].x(), 0.1, 0.011);
  EXPECT_NEAR(box[7].x(), 0.9, 0.011);
  EXPECT_NEAR(box[0].y(), -0.18, 0.0021);
  EXPECT_NEAR(box[7].y(), -0.02, 0.0021);
  for (const Eigen::Vector3d& c : box) EXPECT_LT(c.norm(), 2.0);
  EXPECT_TRUE(centralBoxCorners({}).empty());
}

// The calibration factor scales the prediction; above pose.max_predicted_error_px (> 0) the
// frame is uncertain with the figures in the reason; not tracking: no prediction.
TEST(PredictedOverlayError, CheckScalesAndFlagsAboveTheLimit) {
  PoseTrackingResult tracked;
  tracked.state = TrackingState::Tracking;
  tracked.worldToCamera = cameraPose();
  tracked.T_Ak = RigidPose();
  tracked.covariance = poseCovariance();
  PoseParams params;
  params.predictedErrorScale = 1.0;
  params.maxPredictedErrorPx = 0.0;
  const std::vector<Eigen::Vector3d> points = cube(0.2);
  const OverlayErrorCheck raw = checkPredictedOverlayError(kCamera, tracked, points, params);
  ASSERT_TRUE(raw.predictedErrorPx);
  EXPECT_TRUE(raw.uncertainReason.empty());  // 0: off
  params.predictedErrorScale = 2.5;
  params.maxPredictedErrorPx = 1e6;
  const OverlayErrorCheck scaled = checkPredictedOverlayError(kCamera, tracked, points, params);
  EXPECT_NEAR(*scaled.predictedErrorPx, 2.5 * *raw.predictedErrorPx, 1e-12);
  EXPECT_TRUE(scaled.uncertainReason.empty());
  params.maxPredictedErrorPx = 0.5 * *scaled.predictedErrorPx;
  const OverlayErrorCheck over = checkPredictedOverlayError(kCamera, tracked, points, params);
  EXPECT_NE(over.uncertainReason.find("predicted overlay error"), std::string::npos);
  EXPECT_NE(over.uncertainReason.find("> pose.max_predicted_error_px"), std::string::npos)
      << over.uncertainReason;
  tracked.state = TrackingState::Lost;
  EXPECT_FALSE(checkPredictedOverlayError(kCamera, tracked, points, params).predictedErrorPx);
}

// The a-posteriori rescale: Omega_k's SDs scaled so that at the support points they match the
// support SD the tracker measured (per image axis, so sqrt(2) of it as 2-D RMS). For an object
// made of the support points themselves the prediction is then that measured figure times the
// calibration, whatever Omega_k's size; without support it is Omega_k's own.
TEST(PredictedOverlayError, TheAPosterioriFactorMatchesTheMeasuredSupportSd) {
  PoseTrackingResult tracked;
  tracked.state = TrackingState::Tracking;
  tracked.T_Ak = cameraPose();
  tracked.worldToCamera = cameraPose();  // T_A = identity: the world is camera A's frame
  tracked.covariance = poseCovariance();
  tracked.supportPointsA = cube(0.2);
  tracked.supportSdPx = 0.3;
  PoseParams params;
  params.predictedErrorScale = 1.5;
  const double raw = *predictedOverlayErrorPx(kCamera, cameraPose(), poseCovariance(), cube(0.2));
  EXPECT_NEAR(aPosterioriFactor(kCamera, tracked), std::sqrt(2.0) * 0.3 / raw, 1e-12);
  EXPECT_NEAR(*checkPredictedOverlayError(kCamera, tracked, cube(0.2), params).predictedErrorPx,
              1.5 * std::sqrt(2.0) * 0.3, 1e-12);
  tracked.covariance *= 100.0;  // Omega_k's size does not matter, only its shape
  EXPECT_NEAR(*checkPredictedOverlayError(kCamera, tracked, cube(0.2), params).predictedErrorPx,
              1.5 * std::sqrt(2.0) * 0.3, 1e-12);
  // A larger object: more than the support's figure, in the ratio of Omega_k's predictions.
  const double larger =
      *checkPredictedOverlayError(kCamera, tracked, cube(0.6), params).predictedErrorPx;
  EXPECT_NEAR(larger / (1.5 * std::sqrt(2.0) * 0.3),
              *predictedOverlayErrorPx(kCamera, cameraPose(), poseCovariance(), cube(0.6)) / raw,
              1e-9);
  tracked.supportPointsA.clear();
  EXPECT_EQ(aPosterioriFactor(kCamera, tracked), 1.0);
  tracked.supportPointsA = cube(0.2);
  tracked.supportSdPx = INFINITY;
  EXPECT_EQ(aPosterioriFactor(kCamera, tracked), 1.0);
}

}  // namespace
}  // namespace reftrack
