#include "app/simulator/ExposureIntegration.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "engine/core/Error.hpp"

using namespace reftrack;
using namespace reftrack::app;

namespace {

constexpr int kWidth = 160, kRows = 100;
constexpr double kStartX = 40.0;

// A bright half-plane right of a vertical edge at x = kStartX + speed * t (pixel-area
// anti-aliased: a pixel covers [x - 1/2, x + 1/2]).
cv::Mat movingEdge(double t, double speed) {
  const double edge = kStartX + speed * t;
  cv::Mat image(kRows, kWidth, CV_32FC3);
  for (int x = 0; x < kWidth; ++x) {
    const float v = static_cast<float>(200.0 * std::clamp(x + 0.5 - edge, 0.0, 1.0));
    image.col(x).setTo(cv::Scalar::all(v));
  }
  return image;
}

// Row profile derivative statistics: mean = where the edge is, variance = its spread.
void edgeMoments(const cv::Mat& image, int row, double& mean, double& variance) {
  double sum = 0, first = 0, second = 0;
  for (int x = 1; x < kWidth; ++x) {
    const double d = image.at<cv::Vec3f>(row, x)[0] - image.at<cv::Vec3f>(row, x - 1)[0];
    const double at = x - 0.5;  // between the two pixels
    sum += d;
    first += d * at;
    second += d * at * at;
  }
  mean = first / sum;
  variance = second / sum - mean * mean;
}

}  // namespace

TEST(ExposureIntegration, WithoutExposureOrReadoutIsTheRenderAtTheFrameTime) {
  RowExposureTiming timing;
  timing.rows = kRows;
  EXPECT_EQ(timing.automaticSamples(), 1);
  const cv::Mat out =
      integrateExposure([](double t) { return movingEdge(t, 5.0); }, 3.0, timing, 1);
  EXPECT_EQ(cv::norm(out, movingEdge(3.0, 5.0), cv::NORM_INF), 0.0);
}

TEST(ExposureIntegration, BlurLengthIsThePathMotionOverTheExposure) {
  // 8 px per frame over half a frame: a 4 px box blur. The pixel-difference derivative of the
  // blurred edge is that box convolved with the 1 px pixel box and sampled at pixel spacing:
  // variance (L^2 + 1) / 12 + 1 / 12 (measured on a sharp edge averaged over its sub-pixel
  // positions), so L = sqrt(12 var - 2).
  RowExposureTiming timing;
  timing.rows = kRows;
  timing.exposureFrames = 0.5;
  const double speed = 8.0;
  // Renders h = 1/64 frame (0.125 px) apart: blending renders instead of moving the edge
  // continuously adds 2 h^2 to L^2 (trapezoid weights), 0.002 px on the length here.
  const cv::Mat out =
      integrateExposure([&](double t) { return movingEdge(t, speed); }, 2.0, timing, 33);
  double mean = 0, variance = 0;
  edgeMoments(out, kRows / 2, mean, variance);
  EXPECT_NEAR(std::sqrt(12.0 * variance - 2.0), speed * timing.exposureFrames, 0.02);
  // With the automatic sampling (1/8 frame, 1 px here) the blend of 5 renders is longer by
  // sqrt(L^2 + 2 h^2) - L = 0.24 px, plus up to 1/12 px^2 of sampling variance (the renders'
  // edges all fall on the same sub-pixel phase here): within half a pixel.
  const cv::Mat coarse = integrateExposure([&](double t) { return movingEdge(t, speed); }, 2.0,
                                           timing, timing.automaticSamples());
  double coarseMean = 0, coarseVariance = 0;
  edgeMoments(coarse, kRows / 2, coarseMean, coarseVariance);
  EXPECT_NEAR(std::sqrt(12.0 * coarseVariance - 2.0), speed * timing.exposureFrames, 0.5);
  // Centred on the frame time: the edge's mean position is where it is at t = 2.
  EXPECT_NEAR(mean, kStartX + speed * 2.0, 0.02);
  // Every row the same (no readout delay).
  double mean0 = 0, var0 = 0;
  edgeMoments(out, 0, mean0, var0);
  EXPECT_NEAR(mean0, mean, 1e-4);
}

TEST(ExposureIntegration, RollingShutterSlantsAMovingEdgeByTheLineDelay) {
  // 6 px per frame, 0.004 frame periods per row: the edge moves 0.024 px from row to row.
  RowExposureTiming timing;
  timing.rows = kRows;
  timing.lineDelayFrames = 0.004;
  const double speed = 6.0;
  const cv::Mat out = integrateExposure([&](double t) { return movingEdge(t, speed); }, 1.0, timing,
                                        timing.automaticSamples());
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (int r = 0; r < kRows; ++r) {
    double mean = 0, variance = 0;
    edgeMoments(out, r, mean, variance);
    sx += r;
    sy += mean;
    sxx += r * r;
    sxy += r * mean;
  }
  const double n = kRows;
  const double slope = (n * sxy - sx * sy) / (n * sxx - sx * sx);
  const double intercept = (sy - slope * sx) / n;
  // Each row is interpolated between renders; the edge positions are exact to ~1e-3 px.
  EXPECT_NEAR(slope, speed * timing.lineDelayFrames, 1e-3);
  // The middle row is seen at the frame time.
  EXPECT_NEAR(intercept + slope * 0.5 * (kRows - 1), kStartX + speed * 1.0, 0.01);
}

TEST(ExposureIntegration, RejectsBadInput) {
  RowExposureTiming timing;
  timing.rows = kRows;
  timing.exposureFrames = -1.0;
  EXPECT_THROW(timing.check(), Error);
  timing.exposureFrames = 0.5;
  EXPECT_THROW(integrateExposure([](double) { return cv::Mat(10, 10, CV_8UC3); }, 0.0, timing, 3),
               Error);
  EXPECT_THROW(integrateExposure([](double t) { return movingEdge(t, 1.0); }, 0.0, timing, 0),
               Error);
}
