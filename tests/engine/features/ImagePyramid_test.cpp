#include "engine/features/ImagePyramid.hpp"

#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "engine/core/Error.hpp"
#include "engine/features/SyntheticImages.hpp"

using namespace reftrack;

TEST(ImagePyramid, LevelsArePyrDownOfThePreviousLevelBuiltOnce) {
  const cv::Mat image = test::texturedImage({160, 120}, 7);
  const ImagePyramid pyramid(image);
  EXPECT_EQ(pyramid.image().data, image.data);  // shared, not copied
  EXPECT_EQ(pyramid.level(0).data, image.data);
  const cv::Mat& one = pyramid.level(1);
  const uchar* oneData = one.data;
  cv::Mat expected;
  cv::pyrDown(image, expected);
  ASSERT_EQ(one.size(), expected.size());
  EXPECT_EQ(cv::norm(one, expected, cv::NORM_INF), 0.0);
  // Building a deeper level keeps the earlier ones (same buffer, reference still valid).
  const cv::Mat& three = pyramid.level(3);
  cv::pyrDown(expected, expected);
  cv::pyrDown(expected, expected);
  ASSERT_EQ(three.size(), expected.size());
  EXPECT_EQ(cv::norm(three, expected, cv::NORM_INF), 0.0);
  EXPECT_EQ(one.data, oneData);
  EXPECT_EQ(pyramid.level(1).data, oneData);
}

TEST(ImagePyramid, RejectsBadInput) {
  EXPECT_THROW(ImagePyramid(cv::Mat()), Error);
  EXPECT_THROW(ImagePyramid(cv::Mat(10, 10, CV_32F)), Error);
  EXPECT_THROW(ImagePyramid(cv::Mat(10, 10, CV_8UC3)), Error);
  const ImagePyramid pyramid(cv::Mat(10, 10, CV_8UC1, cv::Scalar(3)));
  EXPECT_THROW(pyramid.level(-1), Error);
}
