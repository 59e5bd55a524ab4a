#include "engine/estimation/MotionModelFitter.hpp"

#include <gtest/gtest.h>

#include <random>

#include "engine/core/Error.hpp"

using namespace reftrack;

namespace {

// Each component follows its own stationary AR(2) process; returned as a TUM trajectory whose
// poses are T_k = fromVector6(x_k) * T_1, so vec(T_k T_1^-1) = x_k exactly.
TumTrajectory ar2Trajectory(const Vector6d& a1, const Vector6d& a2, const Vector6d& sigma, int n,
                            std::vector<Vector6d>* truth) {
  std::mt19937 rng(11);
  std::normal_distribution<double> unit(0.0, 1.0);
  std::vector<Vector6d> x(n, Vector6d::Zero());
  for (int k = 2; k < n; ++k)
    for (int c = 0; c < 6; ++c)
      x[k][c] = a1[c] * x[k - 1][c] + a2[c] * x[k - 2][c] + sigma[c] * unit(rng);
  Vector6d first;
  first << 0.1, -0.05, 0.6, 0.2, -0.1, 0.05;
  const RigidPose T1 = RigidPose::fromVector6(first);
  TumTrajectory traj;
  for (int k = 0; k < n; ++k) traj.poses.push_back({k / 30.0, RigidPose::fromVector6(x[k]) * T1});
  if (truth) *truth = x;
  return traj;
}

}  // namespace

TEST(MotionModelFitter, RecoversKnownAr2Weights) {
  Vector6d a1, a2, sigma;
  a1 << 1.6, 1.2, 0.5, 1.5, 0.9, 1.3;
  a2 << -0.7, -0.4, 0.3, -0.6, -0.2, -0.5;
  sigma << 0.001, 0.001, 0.002, 0.002, 0.001, 0.001;  // m and rad per frame
  std::vector<Vector6d> truth;
  const TumTrajectory traj = ar2Trajectory(a1, a2, sigma, 4000, &truth);
  const std::vector<Vector6d> x = MotionModelFitter::motionVectors(traj);
  ASSERT_EQ(x.size(), truth.size());
  for (std::size_t k = 0; k < x.size(); ++k) ASSERT_LT((x[k] - truth[k]).norm(), 1e-9);

  const FittedMotionModel fit = MotionModelFitter::fit(x, 2);
  ASSERT_EQ(fit.model.order(), 2);
  // The bar: weights within 0.05 (4000 samples give a standard error near 0.01).
  for (int c = 0; c < 6; ++c) {
    EXPECT_NEAR(fit.model.weights()[0][c], a1[c], 0.05) << "component " << c;
    EXPECT_NEAR(fit.model.weights()[1][c], a2[c], 0.05) << "component " << c;
    // Q is the innovation covariance: its diagonal is sigma^2 (within 10% for 4000 samples).
    EXPECT_NEAR(std::sqrt(fit.model.processNoise()(c, c)), sigma[c], 0.1 * sigma[c]);
    EXPECT_GT(fit.explainedVariance[c], 0.0);
    EXPECT_LT(fit.explainedVariance[c], 1.0);
  }
  EXPECT_FALSE(fit.randomWalk);
  EXPECT_EQ(fit.frameCount, 4000);
}

TEST(MotionModelFitter, RandomWalkQIsCovarianceOfFrameChanges) {
  std::mt19937 rng(5);
  std::normal_distribution<double> step(0.0, 0.002);
  std::vector<Vector6d> x(3000, Vector6d::Zero());
  for (std::size_t k = 1; k < x.size(); ++k)
    for (int c = 0; c < 6; ++c) x[k][c] = x[k - 1][c] + step(rng) * (c + 1);
  const FittedMotionModel walk = MotionModelFitter::fit(x, 0);
  EXPECT_TRUE(walk.randomWalk);
  ASSERT_EQ(walk.model.order(), 1);
  EXPECT_TRUE(walk.model.weights()[0].isOnes());
  // Independent computation of cov(dx) with the SPEC's formula.
  Vector6d mean = Vector6d::Zero();
  for (std::size_t k = 1; k < x.size(); ++k) mean += x[k] - x[k - 1];
  mean /= static_cast<double>(x.size() - 1);
  Matrix6d Q = Matrix6d::Zero();
  for (std::size_t k = 1; k < x.size(); ++k) {
    const Vector6d d = x[k] - x[k - 1] - mean;
    Q += d * d.transpose();
  }
  Q /= static_cast<double>(x.size() - 2);
  EXPECT_LT((walk.model.processNoise() - Q).cwiseAbs().maxCoeff(), 1e-11);
  // An AR(1) fit of a random walk finds a weight near 1 (within 0.01: the walk wanders far).
  const FittedMotionModel ar1 = MotionModelFitter::fit(x, 1);
  for (int c = 0; c < 6; ++c) EXPECT_NEAR(ar1.model.weights()[0][c], 1.0, 0.01);
}

TEST(MotionModelFitter, RejectsBadOrderOrTooFewStates) {
  std::vector<Vector6d> few(5, Vector6d::Zero());
  EXPECT_THROW(MotionModelFitter::fit(few, 2), Error);
  std::vector<Vector6d> x(50, Vector6d::Zero());
  EXPECT_THROW(MotionModelFitter::fit(x, -1), Error);
  EXPECT_THROW(MotionModelFitter::fit(x, 21), Error);
  x[3][2] = std::nan("");
  EXPECT_THROW(MotionModelFitter::fit(x, 1), Error);
  EXPECT_TRUE(MotionModelFitter::motionVectors(TumTrajectory{}).empty());
}
