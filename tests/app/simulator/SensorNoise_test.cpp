#include "app/simulator/SensorNoise.hpp"

#include <gtest/gtest.h>

#include "engine/core/Error.hpp"

using namespace reftrack;
using namespace reftrack::app;

TEST(SensorNoise, AddsGaussianNoiseOfTheRequestedSpread) {
  const cv::Mat grey(480, 640, CV_8UC3, cv::Scalar::all(128));
  const cv::Mat noisy = addSensorNoise(grey, 7, 2.0);
  ASSERT_EQ(noisy.type(), CV_8UC3);
  cv::Mat diff;
  noisy.convertTo(diff, CV_64FC3);
  diff -= cv::Scalar::all(128);
  cv::Scalar mean, sd;
  cv::meanStdDev(diff.reshape(1), mean, sd);
  // 921600 samples: the SD estimate has a relative error ~1/sqrt(2n) = 0.07%; rounding to integer
  // grey levels adds 1/12 variance: sqrt(4 + 1/12) = 2.02. 2% tolerance leaves a wide margin.
  EXPECT_NEAR(sd[0], std::sqrt(4.0 + 1.0 / 12.0), 0.04);
  EXPECT_NEAR(mean[0], 0.0, 0.02);
}

TEST(SensorNoise, IsDeterministicInTheSeed) {
  const cv::Mat grey(120, 160, CV_8UC3, cv::Scalar(40, 128, 220));
  const cv::Mat a = addSensorNoise(grey, 42, 3.0), b = addSensorNoise(grey, 42, 3.0);
  const cv::Mat c = addSensorNoise(grey, 43, 3.0);
  EXPECT_EQ(cv::norm(a, b, cv::NORM_INF), 0.0);
  // Different streams: most pixels differ (two independent N(0, 9) draws agree after rounding
  // about 10% of the time).
  cv::Mat same;
  cv::compare(a.reshape(1), c.reshape(1), same, cv::CMP_EQ);
  EXPECT_LT(cv::countNonZero(same), static_cast<int>(0.2 * same.total()));
}

TEST(SensorNoise, ZeroSigmaRoundsAndClampsOnly) {
  cv::Mat f(2, 2, CV_32FC3, cv::Scalar(-5.0, 100.4, 300.0));
  const cv::Mat out = addSensorNoise(f, 1, 0.0);
  EXPECT_EQ(out.at<cv::Vec3b>(1, 1), cv::Vec3b(0, 100, 255));
  EXPECT_THROW(addSensorNoise(cv::Mat(), 1, 1.0), Error);
  EXPECT_THROW(addSensorNoise(cv::Mat(2, 2, CV_8UC1), 1, 1.0), Error);
  EXPECT_THROW(addSensorNoise(f, 1, std::nan("")), Error);
}

TEST(SensorNoise, MixSeedSeparatesNearbyPairs) {
  EXPECT_NE(mixSeed(1, 0), mixSeed(1, 1));
  EXPECT_NE(mixSeed(1, 0), mixSeed(0, 1));
  EXPECT_NE(mixSeed(1, 2), mixSeed(2, 1));
  EXPECT_EQ(mixSeed(5, 9), mixSeed(5, 9));
}
