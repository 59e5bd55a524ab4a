#include "engine/matching/DistinctiveCorners.hpp"

#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "engine/core/Error.hpp"

using namespace reftrack;

// A chessboard's inner corners have look-alikes one square diagonal away; a lone cross of
// another shape, far from the board, has none.
TEST(DistinctiveCorners, ChessboardCornersRepeatALoneShapeDoesNot) {
  cv::Mat image(300, 400, CV_8UC1, cv::Scalar(200));
  const int square = 30;
  for (int r = 0; r < 6; ++r)
    for (int c = 0; c < 6; ++c)
      if ((r + c) % 2 == 0)
        cv::rectangle(image, cv::Rect(20 + c * square, 20 + r * square, square, square),
                      cv::Scalar(30), cv::FILLED);
  // An L-shaped blob and a triangle at the far right.
  cv::rectangle(image, cv::Rect(300, 60, 40, 12), cv::Scalar(60), cv::FILLED);
  cv::rectangle(image, cv::Rect(300, 60, 12, 50), cv::Scalar(60), cv::FILLED);
  const std::vector<cv::Point> triangle = {{320, 200}, {370, 230}, {310, 260}};
  cv::fillConvexPoly(image, triangle, cv::Scalar(90));
  cv::GaussianBlur(image, image, cv::Size(0, 0), 0.8);

  std::vector<cv::Point2f> corners;
  for (int r = 2; r <= 4; ++r)
    for (int c = 2; c <= 4; ++c)
      corners.emplace_back(20.0f + c * square - 0.5f, 20.0f + r * square - 0.5f);  // inner
  const std::size_t boardCorners = corners.size();
  corners.emplace_back(299.5f, 59.5f);   // the L's outer corner
  corners.emplace_back(319.5f, 199.5f);  // a triangle vertex
  const std::vector<char> d = distinctiveCorners(image, corners, 5, 80.0, 0.8);
  ASSERT_EQ(d.size(), corners.size());
  for (std::size_t i = 0; i < boardCorners; ++i) EXPECT_EQ(d[i], 0) << "board corner " << i;
  EXPECT_EQ(d[boardCorners], 1);
  EXPECT_EQ(d[boardCorners + 1], 1);
  // Within a radius smaller than the board's period, nothing repeats.
  const std::vector<char> near = distinctiveCorners(image, corners, 5, 20.0, 0.8);
  for (std::size_t i = 0; i < boardCorners; ++i) EXPECT_EQ(near[i], 1);
}

TEST(DistinctiveCorners, FlatOrBorderWindowsCannotVouchAndBadInputThrows) {
  const cv::Mat flat(100, 100, CV_8UC1, cv::Scalar(128));
  const std::vector<char> d = distinctiveCorners(flat, {{50, 50}, {1, 1}}, 5, 30.0, 0.8);
  EXPECT_EQ(d, (std::vector<char>{0, 0}));
  EXPECT_TRUE(distinctiveCorners(flat, {}, 5, 30.0, 0.8).empty());
  EXPECT_THROW(distinctiveCorners(cv::Mat(), {{1, 1}}, 5, 30.0, 0.8), Error);
  EXPECT_THROW(distinctiveCorners(flat, {{1, 1}}, 0, 30.0, 0.8), Error);
}
