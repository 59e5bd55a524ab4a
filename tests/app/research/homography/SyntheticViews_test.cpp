#include "app/research/homography/SyntheticViews.hpp"

#include <gtest/gtest.h>

#include "engine/core/Error.hpp"
#include "engine/features/SyntheticImages.hpp"

using namespace reftrack;
using namespace reftrack::app;

TEST(SyntheticViews, RelightAppliesGainOffsetAndGradient) {
  const cv::Mat flat(101, 201, CV_8UC1, cv::Scalar(100));
  const cv::Mat same = relight(flat, 1.0, 0.0, {0, 0});
  EXPECT_EQ(cv::norm(same, flat, cv::NORM_INF), 0.0);
  const cv::Mat brighter = relight(flat, 1.2, 5.0, {0, 0});
  EXPECT_EQ(brighter.at<uchar>(50, 100), 125);
  // A gradient of 0.2 along x: the centre unchanged, the right edge (at 100 px of the 111.8 px
  // half diagonal) 0.2 * 100 / 111.8 brighter, the left edge as much darker.
  const cv::Mat lit = relight(flat, 1.0, 0.0, {0.2, 0});
  EXPECT_EQ(lit.at<uchar>(50, 100), 100);
  EXPECT_NEAR(lit.at<uchar>(50, 200), 100 * (1 + 0.2 * 100 / std::hypot(100.0, 50.0)), 1.0);
  EXPECT_NEAR(lit.at<uchar>(50, 0), 100 * (1 - 0.2 * 100 / std::hypot(100.0, 50.0)), 1.0);
  EXPECT_EQ(relight(flat, 3.0, 0.0, {0, 0}).at<uchar>(0, 0), 255);  // saturated
  EXPECT_THROW(relight(cv::Mat(), 1.0, 0.0, {0, 0}), Error);
}

// A frame of another size than the image, seeing beyond its border: mirrored texture there
// (BORDER_REFLECT_101), black with the default border.
TEST(SyntheticViews, SynthesisesAFrameOfAnyOtherSize) {
  const cv::Size size(320, 240);
  const cv::Mat image = test::texturedImage(size, 81);
  const cv::Matx33d H = syntheticViewHomography(size, 40, 90, 0.8, 5);
  const cv::Mat mirrored = synthesiseView(image, H, 0.0, 1, {400, 300}, cv::BORDER_REFLECT_101);
  const cv::Mat black = synthesiseView(image, H, 0.0, 1, {400, 300});
  ASSERT_EQ(mirrored.size(), cv::Size(400, 300));
  ASSERT_EQ(black.size(), cv::Size(400, 300));
  EXPECT_EQ(black.at<uchar>(299, 399), 0);      // beyond the image
  EXPECT_GT(mirrored.at<uchar>(299, 399), 10);  // mirrored texture (the image is >= 20 grey)
  EXPECT_EQ(synthesiseView(image, H, 0.0, 1).size(), size);
}
