#include "engine/estimation/RollingShutterEstimator.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <random>

#include "engine/core/Error.hpp"

using namespace reftrack;

namespace {

constexpr double kF = 500.0, kC = 320.0, kRows = 480.0;

Eigen::Vector2d project(const Eigen::Vector3d& X) {
  return {kF * X.x() / X.z() + kC, kF * X.y() / X.z() + 240.0};
}

// One tracked frame of a rolling-shutter camera: the scene's points seen at a pose slightly off
// the truth (as a tracked pose is), their measurements shifted by the true readout times each
// row's share of the frame's image motion (flow = a random pan, zoom and roll in pixels per
// frame) and corrected with the estimator's readout, plus corner noise (default 0.1 px).
std::vector<RollingShutterObservation> frame(std::mt19937& rng, double trueReadout,
                                             double currentReadout, double motionPx,
                                             double noisePx = 0.1) {
  std::normal_distribution<double> n(0.0, 1.0);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const Eigen::Vector2d pan(motionPx * u(rng), motionPx * u(rng));
  const double zoom = 0.01 * motionPx * u(rng) / 10.0, roll = 0.01 * motionPx * u(rng) / 10.0;
  const Eigen::AngleAxisd poseError(1e-3 * n(rng),
                                    Eigen::Vector3d(n(rng), n(rng), n(rng)).normalized());
  const Eigen::Vector3d poseShift(2e-3 * n(rng), 2e-3 * n(rng), 2e-3 * n(rng));
  std::vector<RollingShutterObservation> out;
  for (int i = 0; i < 150; ++i) {
    const Eigen::Vector3d X(u(rng), 0.7 * u(rng), 2.0 + 0.5 * u(rng));  // true camera frame
    const Eigen::Vector2d truth = project(X);
    const Eigen::Vector2d c(kC, 240.0), d = truth - c;
    const Eigen::Vector2d flow = pan + zoom * d + roll * Eigen::Vector2d(-d.y(), d.x());
    const Eigen::Vector2d g = (truth.y() - 0.5 * (kRows - 1)) / (kRows - 1) * flow;
    const Eigen::Vector2d observed =
        truth + trueReadout * g + noisePx * Eigen::Vector2d(n(rng), n(rng));
    const Eigen::Vector2d measured = observed - currentReadout * g;
    const Eigen::Vector3d tracked = poseError * X + poseShift;
    out.push_back({tracked, project(tracked) - measured, g, noisePx});
  }
  return out;
}

double run(double trueReadout, double motionPx, int frames, std::uint32_t seed) {
  std::mt19937 rng(seed);
  RollingShutterEstimator estimator;
  for (int k = 0; k < frames; ++k)
    estimator.addFrame(kF, kF, frame(rng, trueReadout, estimator.readout(), motionPx));
  return estimator.readout();
}

}  // namespace

// A webcam's readout (0.6 of the frame interval) under hand-held motion of up to 10 px per frame:
// after 40 frames the estimate is within 0.02 of the truth (its SD at these levels is below
// 0.005; the pose error of each frame is projected out, not mistaken for readout).
TEST(RollingShutterEstimator, FindsAWebcamReadout) {
  for (std::uint32_t seed = 1; seed <= 3; ++seed) {
    EXPECT_NEAR(run(0.6, 10.0, 40, seed), 0.6, 0.02) << "seed " << seed;
    EXPECT_NEAR(run(0.25, 10.0, 40, seed), 0.25, 0.02) << "seed " << seed;
  }
}

// A global-shutter camera stays at (about) zero.
TEST(RollingShutterEstimator, GlobalShutterStaysNearZero) {
  for (std::uint32_t seed = 1; seed <= 3; ++seed) EXPECT_LT(run(0.0, 10.0, 60, seed), 0.02);
}

// A camera at rest carries no information about its readout: the start value stays.
TEST(RollingShutterEstimator, NoMotionChangesNothing) {
  std::mt19937 rng(7);
  RollingShutterEstimator estimator(0.3);
  for (int k = 0; k < 50; ++k) estimator.addFrame(kF, kF, frame(rng, 0.6, 0.3, 0.0));
  EXPECT_DOUBLE_EQ(estimator.readout(), 0.3);
  EXPECT_EQ(estimator.updates(), 0);
}

// Too few frames: no estimate is taken before minFrames informative frames (default 10).
TEST(RollingShutterEstimator, WaitsForEnoughFrames) {
  std::mt19937 rng(3);
  RollingShutterEstimator estimator;
  for (int k = 0; k < 9; ++k) estimator.addFrame(kF, kF, frame(rng, 0.6, 0.0, 10.0));
  EXPECT_DOUBLE_EQ(estimator.readout(), 0.0);
  estimator.addFrame(kF, kF, frame(rng, 0.6, 0.0, 10.0));
  EXPECT_NEAR(estimator.readout(), 0.6, 0.05);
}

// Slow motion and noisy corners (1 px of motion per frame, 1.5 px noise, like a slow real clip):
// the estimate of a true 0.3 is too uncertain to be taken (not 3 SDs from 0), so the readout stays
// at its start value instead of wandering with the noise.
TEST(RollingShutterEstimator, AnUncertainEstimateIsNotTaken) {
  for (std::uint32_t seed = 1; seed <= 3; ++seed) {
    std::mt19937 rng(seed);
    RollingShutterEstimator estimator;
    for (int k = 0; k < 30; ++k)
      estimator.addFrame(kF, kF, frame(rng, 0.3, estimator.readout(), 1.0, 1.5));
    EXPECT_DOUBLE_EQ(estimator.readout(), 0.0) << "seed " << seed;
  }
}

TEST(RollingShutterEstimator, RejectsBadSettings) {
  EXPECT_THROW(RollingShutterEstimator(-0.1), Error);
  EXPECT_THROW(RollingShutterEstimator(1.5), Error);
  EXPECT_THROW(RollingShutterEstimator(0.0, 0), Error);
}
