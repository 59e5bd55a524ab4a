#include "engine/evaluation/TrajectoryEvaluator.hpp"

#include <gtest/gtest.h>

#include <numbers>
#include <opencv2/calib3d.hpp>
#include <random>

#include "engine/core/Error.hpp"

using namespace reftrack;

namespace {

// A camera circling the marker at 0.6 m, 30 Hz, looking at the origin.
TumTrajectory orbit(int frames) {
  TumTrajectory traj;
  for (int k = 0; k < frames; ++k) {
    const double a = 0.02 * k;
    const Eigen::Vector3d C(0.4 * std::cos(a), 0.4 * std::sin(a), 0.45);
    const Eigen::Vector3d z = (-C).normalized();
    const Eigen::Vector3d x = z.cross(Eigen::Vector3d::UnitZ()).normalized();
    const Eigen::Vector3d y = z.cross(x);
    Eigen::Matrix3d Rcw;  // camera axes in the world, as columns
    Rcw << x, y, z;
    traj.poses.push_back({k / 30.0, RigidPose(Rcw.transpose(), -Rcw.transpose() * C)});
  }
  return traj;
}

PinholeCamera camera() {
  Eigen::Matrix3d K;
  K << 500, 0, 319.5, 0, 500, 239.5, 0, 0, 1;
  return PinholeCamera(K, {640, 480});
}

}  // namespace

TEST(TrajectoryEvaluator, KnownRigidOffsetGivesKnownAte) {
  const TumTrajectory gt = orbit(200);
  TumTrajectory est = gt;
  const Eigen::Vector3d d(0.003, -0.004, 0.0);  // every camera centre moved by 5 mm
  for (auto& p : est.poses)
    p.worldToCamera = p.worldToCamera * RigidPose(Eigen::Matrix3d::Identity(), -d);
  const PinholeCamera cam = camera();
  const TrajectoryEvaluation ev = evaluateTrajectory(gt, est, {}, &cam);
  EXPECT_EQ(ev.associatedFrames, 200u);
  EXPECT_DOUBLE_EQ(ev.trackedFraction, 1.0);
  EXPECT_NEAR(ev.ateTranslationMm.rmse, 5.0, 1e-9);
  EXPECT_NEAR(ev.ateTranslationMm.median, 5.0, 1e-9);
  EXPECT_NEAR(ev.ateTranslationMm.max, 5.0, 1e-9);
  EXPECT_NEAR(ev.ateRotationDeg.max, 0.0, 1e-6);
  // A constant world offset leaves every relative motion exact. In the camera frame the offset
  // turns smoothly with the camera (0.02 rad per frame), so its second difference is at most
  // 5 mm * 0.02^2 = 0.002 mm: no jitter beyond that.
  EXPECT_NEAR(ev.rpeTranslationMm.max, 0.0, 1e-9);
  EXPECT_LT(*ev.jitterMm, 0.002);

  // Cube error against an independent computation with cv::projectPoints.
  std::vector<cv::Point3d> cube;
  for (const auto& v : cubeVertices(0.1)) cube.emplace_back(v.x(), v.y(), v.z());
  std::vector<double> all;
  for (std::size_t k = 0; k < gt.poses.size(); ++k) {
    std::vector<cv::Point2d> a, b;
    for (const TumTrajectory* traj : {&gt, static_cast<const TumTrajectory*>(&est)}) {
      const RigidPose& T = traj->poses[k].worldToCamera;
      const Vector6d x = T.toVector6();
      cv::projectPoints(cube, cv::Vec3d(x[3], x[4], x[5]), cv::Vec3d(x[0], x[1], x[2]), cam.Kcv(),
                        cv::noArray(), traj == &gt ? a : b);
    }
    for (std::size_t v = 0; v < cube.size(); ++v) all.push_back(cv::norm(a[v] - b[v]));
  }
  const ErrorStats ref = ErrorStats::of(all);
  ASSERT_TRUE(ev.cubeErrorPx.has_value());
  EXPECT_NEAR(ev.cubeErrorPx->mean, ref.mean, 1e-9);
  EXPECT_NEAR(ev.cubeErrorPx->p95, ref.p95, 1e-9);
  // 5 mm at about 0.6 m with f = 500 px: a few pixels.
  EXPECT_GT(ref.mean, 2.0);
  EXPECT_LT(ref.mean, 6.0);

  // Aligned, the rigid offset vanishes.
  EvaluationParams aligned;
  aligned.align = true;
  EXPECT_NEAR(evaluateTrajectory(gt, est, aligned, &cam).ateTranslationMm.max, 0.0, 1e-6);
}

TEST(TrajectoryEvaluator, JitterRecoversWhiteNoiseAndTrackedFractionCountsGaps) {
  const TumTrajectory gt = orbit(3000);
  TumTrajectory est;
  std::mt19937 rng(7);
  std::normal_distribution<double> noise(0.0, 0.001);  // 1 mm per coordinate, camera frame
  for (std::size_t k = 0; k < gt.poses.size(); ++k) {
    if (k % 10 == 9) continue;  // every tenth frame lost
    const Eigen::Vector3d n(noise(rng), noise(rng), noise(rng));
    est.poses.push_back({gt.poses[k].timestamp + 0.001,
                         RigidPose(Eigen::Matrix3d::Identity(), n) * gt.poses[k].worldToCamera});
  }
  const TrajectoryEvaluation ev = evaluateTrajectory(gt, est, {});
  EXPECT_NEAR(ev.trackedFraction, 0.9, 1e-12);
  // A camera-frame translation moves every cube vertex by the same noise, so the jitter estimate
  // is the noise SD: 1 mm; with ~2100 triplets its sampling error is about 2%, allow 5%.
  ASSERT_TRUE(ev.jitterMm.has_value());
  EXPECT_NEAR(*ev.jitterMm, 1.0, 0.05);
  // ATE of isotropic 3D noise of 1 mm per axis: RMSE sqrt(3) mm.
  EXPECT_NEAR(ev.ateTranslationMm.rmse, std::sqrt(3.0), 0.05);
  EXPECT_FALSE(ev.cubeErrorPx.has_value());
}

TEST(TrajectoryEvaluator, RejectsEmptyOrUnassociatedInput) {
  const TumTrajectory gt = orbit(10);
  TumTrajectory late = gt;
  for (auto& p : late.poses) p.timestamp += 100.0;
  EXPECT_THROW(evaluateTrajectory(gt, TumTrajectory{}, {}), Error);
  EXPECT_THROW(evaluateTrajectory(gt, late, {}), Error);
  EvaluationParams bad;
  bad.cubeSide = std::nan("");
  EXPECT_THROW(evaluateTrajectory(gt, gt, bad), Error);
}

TEST(ErrorStats, MatchesHandComputedValues) {
  const ErrorStats s = ErrorStats::of({3, 1, 2, 4});
  EXPECT_DOUBLE_EQ(s.mean, 2.5);
  EXPECT_DOUBLE_EQ(s.median, 2.5);
  EXPECT_DOUBLE_EQ(s.max, 4);
  EXPECT_DOUBLE_EQ(s.rmse, std::sqrt(30.0 / 4));
  EXPECT_DOUBLE_EQ(s.p95, 3.85);  // 0.95 * 3 = 2.85 -> 3 + 0.85 * (4 - 3)
}
