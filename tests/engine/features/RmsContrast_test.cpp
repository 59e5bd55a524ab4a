#include "engine/features/RmsContrast.hpp"

#include <gtest/gtest.h>

#include "engine/core/Error.hpp"

using namespace reftrack;

TEST(RmsContrast, FlatIsZeroAndEdgeMatchesClosedForm) {
  cv::Mat flat(40, 40, CV_8UC1, cv::Scalar(77));
  EXPECT_DOUBLE_EQ(rmsContrast(flat, {20, 20}, 15), 0.0);
  // Columns < 20 are 0, >= 20 are 100: the 15x15 window at x = 20 holds 7 dark and 8 bright
  // columns, so the SD is 100 * sqrt(7/15 * 8/15).
  cv::Mat edge(40, 40, CV_8UC1, cv::Scalar(0));
  edge.colRange(20, 40).setTo(100);
  EXPECT_NEAR(rmsContrast(edge, {20, 20}, 15), 100 * std::sqrt(7.0 / 15 * 8.0 / 15), 1e-9);
}

TEST(RmsContrast, ClipsAtBorderAndRejectsBadInput) {
  cv::Mat img(10, 10, CV_8UC1, cv::Scalar(5));
  EXPECT_DOUBLE_EQ(rmsContrast(img, {0, 0}, 15), 0.0);
  EXPECT_THROW(rmsContrast(cv::Mat(), {0, 0}, 15), Error);
  EXPECT_THROW(rmsContrast(img, {0, 0}, 14), Error);
  EXPECT_THROW(rmsContrast(cv::Mat(10, 10, CV_32F), {0, 0}, 15), Error);
}
