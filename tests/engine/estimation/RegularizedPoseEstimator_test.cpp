#include "engine/estimation/RegularizedPoseEstimator.hpp"

#include <gtest/gtest.h>

#include <random>

using namespace reftrack;

namespace {

struct SyntheticFrame {
  Eigen::Matrix3d K;
  RigidPose T_AB, T_Ak;
  std::vector<Eigen::Vector3d> points;  // camera A frame
  SyntheticFrame() {
    K << 520, 0, 319.5, 0, 520, 239.5, 0, 0, 1;
    T_AB = RigidPose::fromVector6((Vector6d() << -0.25, 0.02, 0.03, 0.02, -0.2, 0.01).finished());
    T_Ak = RigidPose::fromVector6((Vector6d() << 0.06, -0.02, 0.04, -0.05, 0.12, 0.03).finished());
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> ux(-0.5, 0.5), uz(0.8, 2.0);
    while (points.size() < 120) {
      const Eigen::Vector3d P(ux(rng), 0.75 * ux(rng), uz(rng));
      if (inView(RigidPose(), P) && inView(T_AB, P) && inView(T_Ak, P)) points.push_back(P);
    }
  }
  Eigen::Vector2d project(const RigidPose& T, const Eigen::Vector3d& P) const {
    const Eigen::Vector3d q = K * (T * P);
    return q.head<2>() / q.z();
  }
  bool inView(const RigidPose& T, const Eigen::Vector3d& P) const {
    if ((T * P).z() < 0.1) return false;
    const Eigen::Vector2d p = project(T, P);
    return p.x() > 0 && p.y() > 0 && p.x() < 640 && p.y() < 480;
  }
  PoseMeasurements measure(double sigma, std::mt19937& rng, bool withB = true,
                           bool withThree = true) const {
    std::normal_distribution<double> n(0.0, sigma);
    const auto noisy = [&](const Eigen::Vector2d& p) -> Eigen::Vector2d {
      return p + Eigen::Vector2d(n(rng), n(rng));
    };
    // Variance of a point-to-line distance with noise in both points ~ 2 sigma^2.
    const double s2 = std::sqrt(2.0) * sigma;
    PoseMeasurements m;
    for (size_t i = 0; i < points.size(); ++i) {
      const Eigen::Vector3d& P = points[i];
      // Independent noise per term, so the terms are independent measurements.
      m.toA.push_back({noisy(project(RigidPose(), P)), noisy(project(T_Ak, P)), s2});
      if (withB) m.toB.push_back({noisy(project(T_AB, P)), noisy(project(T_Ak, P)), s2});
      if (withThree && i % 2 == 0) m.threeView.push_back({P, noisy(project(T_Ak, P)), sigma});
    }
    return m;
  }
};

double translationErrorMm(const Vector6d& x, const RigidPose& truth) {
  return 1000 * RigidPose::translationDistance(RigidPose::fromVector6(x), truth);
}
double rotationErrorDeg(const Vector6d& x, const RigidPose& truth) {
  return RigidPose::rotationDistance(RigidPose::fromVector6(x), truth) * 180 / M_PI;
}

}  // namespace

TEST(RegularizedPoseEstimator, StandardLeastSquaresRecoversPoseFromAllTerms) {
  const SyntheticFrame f;
  std::mt19937 rng(1);
  const PoseMeasurements m = f.measure(0.3, rng);
  const RegularizedPoseEstimator est(f.K, f.T_AB);
  const auto start = est.linearStart(m.threeView);
  ASSERT_TRUE(start.has_value());
  const PoseEstimate e = est.estimateStandard(m, *start);
  EXPECT_TRUE(e.covarianceValid);
  // 120 points at 0.8-2 m with 0.3 px noise: expected errors of about a millimetre and a few
  // hundredths of a degree; the bounds leave a factor ~3.
  EXPECT_LT(translationErrorMm(e.x, f.T_Ak), 3.0);
  EXPECT_LT(rotationErrorDeg(e.x, f.T_Ak), 0.1);
}

TEST(RegularizedPoseEstimator, EpipolarTermsOfBothReferencesFixTheScale) {
  const SyntheticFrame f;
  std::mt19937 rng(2);
  const RegularizedPoseEstimator est(f.K, f.T_AB);
  // Start 2 cm and ~1 degree away; no three-view terms: scale must come from V_B.
  Vector6d start = f.T_Ak.toVector6();
  start += (Vector6d() << 0.02, -0.01, 0.015, 0.01, -0.01, 0.01).finished();
  const PoseEstimate e = est.estimateStandard(f.measure(0.2, rng, true, false), start);
  EXPECT_LT(translationErrorMm(e.x, f.T_Ak), 5.0);
  EXPECT_LT(rotationErrorDeg(e.x, f.T_Ak), 0.1);
}

TEST(RegularizedPoseEstimator, CovarianceMatchesEmpiricalScatter) {
  const SyntheticFrame f;
  std::mt19937 rng(3);
  const RegularizedPoseEstimator est(f.K, f.T_AB);
  const Vector6d truth = f.T_Ak.toVector6();
  double meanMahalanobis = 0;
  const int trials = 60;
  for (int t = 0; t < trials; ++t) {
    const PoseEstimate e = est.estimateStandard(f.measure(0.5, rng), truth);
    ASSERT_TRUE(e.covarianceValid);
    const Vector6d d = e.x - truth;
    meanMahalanobis += d.dot(e.covariance.inverse() * d) / trials;
  }
  // A consistent covariance gives a chi-square with 6 dof: mean 6 (sd of the mean ~0.45 here).
  EXPECT_GT(meanMahalanobis, 3.5);
  EXPECT_LT(meanMahalanobis, 9.0);
}

TEST(RegularizedPoseEstimator, PriorPullsTowardsPredictionByAlpha) {
  const SyntheticFrame f;
  std::mt19937 rng(4);
  const RegularizedPoseEstimator est(f.K, f.T_AB);
  const PoseMeasurements m = f.measure(1.0, rng);
  const Vector6d truth = f.T_Ak.toVector6();
  const Vector6d xPred = truth + (Vector6d() << 0.01, 0, 0, 0, 0.005, 0).finished();
  const Matrix6d omega = ArMotionModel::diagonalNoise(0.0005, 0.0005);
  const PoseEstimate weak = est.estimateRegularised(m, xPred, omega, 1e-6);
  const PoseEstimate strong = est.estimateRegularised(m, xPred, omega, 1e4);
  EXPECT_LT((weak.x - truth).norm(), (strong.x - truth).norm());
  EXPECT_LT((strong.x - xPred).norm(), 1e-3);
  // The prior adds information: the covariance shrinks.
  EXPECT_LT(strong.covariance.trace(), weak.covariance.trace());
}
