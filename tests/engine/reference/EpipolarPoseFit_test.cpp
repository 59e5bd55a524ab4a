#include "engine/reference/EpipolarPoseFit.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "engine/geometry/FundamentalMatrix.hpp"

using namespace reftrack;

namespace {

constexpr double kDeg = M_PI / 180.0;

// 640x480, f = 525 (the Kinect's), points 0.8-3 m in front of view 1; view 2 15 cm to the side
// and turned 8 degrees: the relative pose of the kinect-kitchen references 200/220.
struct Scene {
  Eigen::Matrix3d K;
  RigidPose truth;
  std::vector<Eigen::Vector2d> p1, p2;
  explicit Scene(double noisePx, double outlierShare, unsigned seed = 3) {
    K << 525, 0, 320, 0, 525, 240, 0, 0, 1;
    truth = RigidPose(Eigen::AngleAxisd(8.0 * kDeg, Eigen::Vector3d(0.2, 1.0, 0.1).normalized())
                          .toRotationMatrix(),
                      Eigen::Vector3d(-0.15, 0.01, 0.02));
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> x(-1.0, 1.0), depth(0.8, 3.0), u(0.0, 1.0),
        pixel(0.0, 640.0);
    std::normal_distribution<double> noise(0.0, noisePx);
    while (p1.size() < 150) {
      const double z = depth(rng);
      const Eigen::Vector3d P(0.55 * x(rng) * z, 0.4 * x(rng) * z, z);
      const Eigen::Vector3d Q = truth * P;
      if (Q.z() < 0.1) continue;
      p1.emplace_back((K * P).hnormalized());
      Eigen::Vector2d b = (K * Q).hnormalized() + Eigen::Vector2d(noise(rng), noise(rng));
      if (u(rng) < outlierShare) b = Eigen::Vector2d(pixel(rng), 0.75 * pixel(rng));
      p2.push_back(b);
    }
  }
};

RigidPose turned(const RigidPose& T, double deg, const Eigen::Vector3d& axis) {
  return RigidPose(Eigen::AngleAxisd(deg * kDeg, axis.normalized()).toRotationMatrix(),
                   Eigen::Vector3d::Zero()) *
         T;
}

}  // namespace

TEST(EpipolarPoseFit, ExactPosesAgreeWithTheirOwnCorrespondences) {
  const Scene s(0.2, 0.0);
  const EpipolarPoseFit fit = fitEpipolarPose(s.K, s.truth, s.p1, s.p2);
  EXPECT_EQ(fit.correspondences, 150);
  EXPECT_GE(fit.inliers, 148);  // 0.2 px noise: all within 2 px
  // Both poses explain the noise (median |N(0, 0.2)| ~ 0.13 px); the fit takes up a few
  // hundredths of a pixel of it, the 5 degrees of freedom's share.
  EXPECT_LT(fit.givenMedianPx, 0.2);
  EXPECT_LT(fit.fittedMedianPx, fit.givenMedianPx + 1e-9);
  EXPECT_GT(fit.fittedMedianPx, 0.7 * fit.givenMedianPx);
  EXPECT_LT(fit.rotationChangeDeg, 0.05);
  EXPECT_LT(fit.translationDirectionChangeDeg, 2.0);
}

TEST(EpipolarPoseFit, APoseOneDegreeOffIsFoundFromTheCorrespondences) {
  // A quarter of the correspondences are wrong (uniform over the image): the Cauchy loss keeps
  // them from pulling the fit.
  const Scene s(0.3, 0.25);
  const RigidPose given = turned(s.truth, 1.0, Eigen::Vector3d(1.0, 0.3, 0.0));
  const EpipolarPoseFit fit = fitEpipolarPose(s.K, given, s.p1, s.p2);
  ASSERT_TRUE(fit.converged);
  // One degree at f = 525 moves the lines by up to ~9 px: the given pose explains the right
  // correspondences to several pixels, the fitted one to their noise (median |N(0, 0.3)| ~ 0.2).
  EXPECT_GT(fit.givenMedianPx, 2.0);
  EXPECT_LT(fit.fittedMedianPx, 0.35);
  EXPECT_GE(fit.inliers, 105);  // ~112 right ones, and the few wrong ones that land near a line
  // The fitted pose is the true one to the precision 150 noisy correspondences give.
  EXPECT_LT(RigidPose::rotationDistance(fit.fitted, s.truth) / kDeg, 0.1);
  EXPECT_NEAR(fit.rotationChangeDeg, 1.0, 0.1);
  EXPECT_NEAR(fit.fitted.translation().norm(), s.truth.translation().norm(), 1e-9);
  EXPECT_LT(
      std::acos(fit.fitted.translation().normalized().dot(s.truth.translation().normalized())) /
          kDeg,
      2.0);
}

TEST(EpipolarPoseFit, TooFewCorrespondencesLeaveTheGivenPose) {
  const Scene s(0.2, 0.0);
  const std::vector<Eigen::Vector2d> a(s.p1.begin(), s.p1.begin() + 5),
      b(s.p2.begin(), s.p2.begin() + 5);
  const RigidPose given = turned(s.truth, 1.0, Eigen::Vector3d::UnitX());
  const EpipolarPoseFit fit = fitEpipolarPose(s.K, given, a, b);
  EXPECT_EQ(fit.inliers, 0);
  EXPECT_FALSE(fit.converged);
  EXPECT_LT(RigidPose::rotationDistance(fit.fitted, given), 1e-12);
}
