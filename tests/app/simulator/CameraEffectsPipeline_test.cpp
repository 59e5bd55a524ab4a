#include "app/simulator/CameraEffectsPipeline.hpp"

#include <gtest/gtest.h>

#include "app/simulator/PhotometricEffects.hpp"
#include "engine/core/Error.hpp"

using namespace reftrack;
using namespace reftrack::app;

namespace {

// A static scene: a smooth horizontal ramp 60..180 (no motion, so no blur or shutter effect).
cv::Mat staticScene(double) {
  cv::Mat image(120, 160, CV_32FC3);
  for (int x = 0; x < 160; ++x) image.col(x).setTo(cv::Scalar::all(60.0 + 0.75 * x));
  return image;
}

CameraSetup setup(int frames) {
  CameraSetup s;
  s.size = {160, 120};
  s.fps = 10.0;
  s.frames = frames;
  s.seed = 5;
  s.noiseSigma = 0.0;
  return s;
}

}  // namespace

TEST(CameraEffectsPipeline, ExposureStepChangesTheMeanIntensityByTheGainRatio) {
  CameraEffects e;
  e.gainStep = 0.2;
  e.gainStepSeconds = 1.0;  // 10 frames per level
  CameraEffectsPipeline pipeline(e, setup(30), staticScene);
  const double before = cv::mean(pipeline.frame(9))[0], after = cv::mean(pipeline.frame(10))[0];
  const double expected = autoExposureGain(5, 1.0, 0.2, 1.0) / autoExposureGain(5, 0.9, 0.2, 1.0);
  // 8-bit rounding of a 19200-pixel mean: far below 0.1%.
  EXPECT_NEAR(after / before, expected, 1e-3);
  EXPECT_GT(std::abs(expected - 1.0), 1e-3);                        // it is a step
  EXPECT_NEAR(cv::mean(pipeline.frame(3))[0] / before, 1.0, 1e-3);  // same level, same mean
}

TEST(CameraEffectsPipeline, IsDeterministicAndCountsCompressedBytes) {
  CameraEffects e;
  e.codec = "h264";
  e.groupFrames = 5;
  e.poissonNoise = true;
  e.vignetting = 0.3;
  CameraEffectsPipeline a(e, setup(12), staticScene), b(e, setup(12), staticScene);
  for (int k : {0, 4, 7, 11}) EXPECT_EQ(cv::norm(a.frame(k), b.frame(k), cv::NORM_INF), 0.0);
  EXPECT_EQ(a.encodedFrames(), 12);  // three groups: 0-4, 5-9, 10-11
  EXPECT_GT(a.encodedBytes(), 0u);
  EXPECT_LT(a.encodedBytes(), 12u * 160u * 120u * 3u / 10u);
  EXPECT_THROW(a.frame(12), Error);
  // Vignetting survives the codec: corners darker than the centre column's same-ramp pixels.
  const cv::Mat f = a.frame(0);
  EXPECT_LT(f.at<cv::Vec3b>(2, 80)[0], f.at<cv::Vec3b>(60, 80)[0]);
}

TEST(CameraEffectsPipeline, StillsGetOpticsAndNoiseButNoGainOrFlicker) {
  CameraEffects e;
  e.gainStep = 0.5;
  e.flickerAmplitude = 0.5;
  const CameraEffectsPipeline pipeline(e, setup(3), staticScene);
  cv::Mat clean8;
  staticScene(0).convertTo(clean8, CV_8UC3);
  EXPECT_EQ(cv::norm(pipeline.still(clean8, 1), clean8, cv::NORM_INF), 0.0);
}
