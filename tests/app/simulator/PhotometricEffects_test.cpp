#include "app/simulator/PhotometricEffects.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "engine/core/Error.hpp"

using namespace reftrack;
using namespace reftrack::app;

TEST(PhotometricEffects, DefocusSpreadsAnEdgeAsADiscOfTheRadius) {
  // The line-spread function of a uniform disc of radius R has variance R^2 / 4.
  const double radius = 3.0;
  const cv::Mat kernel = defocusKernel(radius);
  EXPECT_EQ(kernel.rows, 7);
  EXPECT_NEAR(cv::sum(kernel)[0], 1.0, 1e-6);
  cv::Mat step(40, 80, CV_32FC3, cv::Scalar::all(0));
  step.colRange(40, 80).setTo(cv::Scalar::all(100));
  const cv::Mat blurred = defocus(step, radius);
  double sum = 0, first = 0, second = 0;
  for (int x = 1; x < 80; ++x) {
    const double d = blurred.at<cv::Vec3f>(20, x)[1] - blurred.at<cv::Vec3f>(20, x - 1)[1];
    sum += d;
    first += d * x;
    second += d * x * x;
  }
  const double variance = second / sum - (first / sum) * (first / sum);
  // Pixel-area sampling of the disc edge: within 5% of R^2 / 4.
  EXPECT_NEAR(variance, radius * radius / 4.0, 0.05 * radius * radius / 4.0);
  EXPECT_EQ(cv::norm(defocus(step, 0.0), step, cv::NORM_INF), 0.0);
  EXPECT_THROW(defocusKernel(-1.0), Error);
}

TEST(PhotometricEffects, VignettingDimsTheCornersByItsStrength) {
  const cv::Mat gain = vignettingGain({101, 81}, 0.3);
  EXPECT_NEAR(gain.at<float>(40, 50), 1.0f, 1e-6);
  EXPECT_NEAR(gain.at<float>(0, 0), 0.7f, 1e-6);
  EXPECT_NEAR(gain.at<float>(80, 100), 0.7f, 1e-6);
  EXPECT_THROW(vignettingGain({10, 10}, 1.5), Error);
}

TEST(PhotometricEffects, AutoExposureGainStepsOnlyAtItsInterval) {
  EXPECT_EQ(autoExposureGain(7, 0.5, 0.1, 1.0), 1.0);  // first interval
  int changes = 0;
  double previous = autoExposureGain(7, 0.0, 0.1, 1.0);
  for (int i = 1; i < 160; ++i) {  // 1/16 s steps: exact in binary
    const double g = autoExposureGain(7, i * 0.0625, 0.1, 1.0);
    EXPECT_GE(g, 0.9);
    EXPECT_LE(g, 1.1);
    if (g != previous) ++changes;
    EXPECT_TRUE(i % 16 == 0 || g == previous) << "changed inside an interval at " << i / 16.0;
    previous = g;
  }
  EXPECT_GE(changes, 8);  // 9 interval boundaries; levels are continuous random numbers
  EXPECT_EQ(autoExposureGain(7, 5.5, 0.0, 1.0), 1.0);
}

TEST(PhotometricEffects, FlickerBandsRepeatAtTheLightPeriodOverTheLineDelay) {
  // 100 Hz light, 30 fps, 20 us per row: bands repeat every 1 / (100 Hz * 20 us) = 500 rows.
  RowExposureTiming timing;
  timing.rows = 1200;
  const double fps = 30.0, lineDelaySeconds = 20e-6;
  timing.lineDelayFrames = lineDelaySeconds * fps;
  const cv::Mat g = flickerRowGain(timing, 0.0, fps, 0.2, 100.0);
  // The lag (rows) where the gain best repeats itself.
  int bestLag = 0;
  double best = 1e30;
  for (int lag = 100; lag < 700; ++lag) {
    double ss = 0;
    for (int r = 0; r + lag < timing.rows; ++r) {
      const double d = g.at<float>(r) - g.at<float>(r + lag);
      ss += d * d;
    }
    ss /= timing.rows - lag;
    if (ss < best) {
      best = ss;
      bestLag = lag;
    }
  }
  EXPECT_NEAR(bestLag, 1.0 / (100.0 * lineDelaySeconds), 1.0);
  double lo = 1e9, hi = -1e9;
  for (int r = 0; r < timing.rows; ++r) {
    lo = std::min(lo, static_cast<double>(g.at<float>(r)));
    hi = std::max(hi, static_cast<double>(g.at<float>(r)));
  }
  EXPECT_NEAR(hi - lo, 0.4, 1e-3);  // +-amplitude
  // An exposure of exactly one light period (10 ms) integrates the flicker away.
  timing.exposureFrames = 0.01 * fps;
  const cv::Mat flat = flickerRowGain(timing, 0.0, fps, 0.2, 100.0);
  for (int r = 0; r < timing.rows; r += 37) EXPECT_NEAR(flat.at<float>(r), 1.0f, 1e-6);
}

TEST(PhotometricEffects, PoissonGaussianNoiseVarianceGrowsWithTheSignal) {
  const double gain = 0.1, read = 1.5;
  for (const double level : {40.0, 180.0}) {
    const cv::Mat flat(200, 200, CV_32FC3, cv::Scalar::all(level));
    const cv::Mat noisy = addPoissonGaussianNoise(flat, 11, gain, read);
    cv::Scalar mean, sd;
    cv::meanStdDev(noisy.reshape(1), mean, sd);
    // Rounding to 8 bits adds 1/12; 120000 samples give ~0.4% relative error of the variance.
    const double expected = gain * level + read * read + 1.0 / 12.0;
    EXPECT_NEAR(sd[0] * sd[0], expected, 0.03 * expected) << "level " << level;
    EXPECT_NEAR(mean[0], level, 0.05);
  }
  EXPECT_THROW(addPoissonGaussianNoise(cv::Mat(4, 4, CV_8UC3), 1, 0.1, 1.0), Error);
}
