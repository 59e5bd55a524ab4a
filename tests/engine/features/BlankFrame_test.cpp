#include "engine/features/BlankFrame.hpp"

#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "engine/tracking/TrackingTestImages.hpp"

namespace reftrack {
namespace {

// Black, uniform grey and a dark frame with sensor noise (sigma 3 levels: averaged away in the
// 8x8-pixel cells of the thumbnail) are blank; a textured frame, a dim one (its texture scaled to
// a tenth) and a frame with one bright object on black are not.
TEST(BlankFrame, UniformAndNoisyDarkFramesAreBlankAnyTextureIsNot) {
  const cv::Size size(640, 480);
  EXPECT_TRUE(isBlankFrame(cv::Mat::zeros(size, CV_8UC3)));
  EXPECT_TRUE(isBlankFrame(cv::Mat(size, CV_8UC1, cv::Scalar(128))));
  EXPECT_TRUE(isBlankFrame(cv::Mat()));
  cv::Mat noisy(size, CV_8UC1);
  cv::RNG(5).fill(noisy, cv::RNG::NORMAL, 12, 3);
  EXPECT_TRUE(isBlankFrame(noisy));

  const cv::Mat textured = test::texturedImage(size, 3);
  EXPECT_FALSE(isBlankFrame(textured));
  cv::Mat dim;
  textured.convertTo(dim, -1, 0.1);
  EXPECT_FALSE(isBlankFrame(dim));
  cv::Mat object = cv::Mat::zeros(size, CV_8UC3);
  cv::rectangle(object, cv::Rect(300, 200, 60, 60), cv::Scalar::all(255), cv::FILLED);
  EXPECT_FALSE(isBlankFrame(object));
}

}  // namespace
}  // namespace reftrack
